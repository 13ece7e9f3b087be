/// climbsim-drive: the multibody drive service (docs/design.md#models). Reads DriveCommand and
/// AdhesionForce; writes RobotState and DriveState every due step. The model substeps at
/// --substep-hz inside the participant's period. With --scenario the robot, start pose, wall and
/// substep rate come from the scenario file (rates.drive_hz); the options that set them
/// explicitly are then refused, so that a run is configured in one place (configure.hpp).

#include <spdlog/spdlog.h>

#include "climbsim/logging.hpp"
#include "climbsim/service_command_line.hpp"
#include "configure.hpp"
#include "node/drive_participant.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  ServiceCommandLine cli("climbsim-drive: the robot's multibody dynamics on the wall (Simbody)",
                         "scenario file (deploy/scenarios/*.yaml): robot, start pose, wall and substep rate "
                         "(rates.drive_hz) come from it; excludes --robot, --x-m, --y-m, --yaw-deg, --wall, "
                         "--substep-hz, --hold-s",
                         "start.x_m=2");
  drive::DriveOverrides o;
  CLI::App& app = cli.app;
  for (auto* option : {
           cli.addRobotOption(),
           app.add_option("--x-m", o.x_m, "start position of the robot centre on the wall, W's x [m]"),
           app.add_option("--y-m", o.y_m, "start position of the robot centre on the wall, W's y [m]"),
           app.add_option("--yaw-deg", o.yaw_deg, "start heading: angle of R's x from W's x [deg]"),
           app.add_option("--wall", o.wall, "vertical, floor, ceiling or overhang:DEG (degrees beyond vertical)"),
           app.add_option("--substep-hz", o.substep_hz, "integration rate of the model [Hz], 100..100000"),
           app.add_option("--hold-s", o.hold_s, "the chassis is held at its start pose until this time [s]")}) {
    option->excludes(cli.scenario_option);
  }
  app.add_option("--inputs", o.inputs,
                 "inputs to read, comma-separated from command,adhesion, or none; an absent one keeps its "
                 "default (standing still; --downforce at the centre)");
  app.add_option("--downforce", o.downforce_n,
                 "adhesion force until thermo/AdhesionForce arrives, or for the whole run without it [N] "
                 "(default: 0 until it arrives, as thermo's initial state; without the adhesion input the "
                 "robot's adhesion.desired_downforce_n)");
  app.add_option("--contact", o.contact,
                 "force backend: direct (the model's own forces from Simbody's kinematics, the default) or simbody "
                 "(Simbody's contact subsystem and force elements: the same physics, slower; the reference)");
  return cli.run(argc, argv, "drive", [&]() -> int {
    initLogging(cli.participant.name);
    const ScenarioAndRobot run = cli.load();
    const drive::DriveSetup setup = drive::configureDrive(run, o, thisBuildDir());
    if (const auto& s = run.scenario) {
      spdlog::info("drive: scenario {}: start x = {} m, y = {} m, yaw = {} deg; wall {} (overhang {} deg); {} Hz "
                   "substeps",
                   s->name, s->start.x_m, s->start.y_m, s->start.yaw_deg, toString(s->wall.kind),
                   s->wall.overhang_deg, s->rates.drive_hz);
    }
    spdlog::info("drive: force backend {}", drive::toString(setup.params.contact_backend));
    drive::DriveNode node(setup.params, setup.wall, setup.start, setup.downforce_n);
    node.holdUntil(setup.hold_until_ns);
    return drive::runDriveParticipant(cli.participant, setup, node);
  });
}
