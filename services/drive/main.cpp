/// climbsim-drive: the multibody drive service (DESIGN.md §1.1). Reads DriveCommand and
/// AdhesionForce; writes RobotState and DriveState every due step. The model substeps at
/// --substep-hz inside the participant's period. With --scenario the robot, start pose, wall and
/// substep rate come from the scenario file (rates.drive_hz); the options that set them
/// explicitly are then refused, so that a run is configured in one place.

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "node/drive_node.hpp"
#include "node/drive_translate.hpp"
#include "node/wheels_over_scene.hpp"
#include "params_from_robot.hpp"
#include "climbsim/wall/scene.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "robotPubSubTypes.h"
#include "thermoPubSubTypes.h"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

namespace {

climbsim::drive::WallOrientation wallFromScenario(const climbsim::Scenario::Wall& wall) {
  using climbsim::drive::WallOrientation;
  switch (wall.kind) {
    case climbsim::Scenario::WallKind::kFloor: return WallOrientation::floor();
    case climbsim::Scenario::WallKind::kOverhang: return WallOrientation::overhang(wall.overhang_deg);
    case climbsim::Scenario::WallKind::kVertical: break;
  }
  return WallOrientation::vertical();
}

/// The wheel check of wheels_over_scene.hpp, loaded in the background while the run starts.
std::optional<climbsim::drive::WheelsOverScene> wheelCheck(const std::string& scene_file,
                                                          const std::vector<climbsim::drive::WheelMount>& wheels) {
  // A background chore while every process of the run starts: at a lower priority than the
  // DDS threads of this and the other processes (their leases are 1 s on a busy machine).
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
  return climbsim::drive::wheelCheckOnScene(scene_file, wheels);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-drive: the robot's multibody dynamics on the wall (Simbody)"};
  ParticipantOptions options;
  std::string robot_file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  std::string inputs_list = "command,adhesion";
  std::string wall_text = "vertical";
  double x_m = 0.0, y_m = 0.0, yaw_deg = 0.0;
  double substep_hz = 1000.0;
  double downforce_n = std::nan("");
  double hold_s = 0.0;
  bool end_on_fall = false;  ///< from the scenario's end_on.fall; without a scenario a fall never ends the run
  std::string contact_text = "direct";
  std::string scenario_file;
  std::string scene_file;  ///< the scenario's scene: the wheels are checked against it
  std::vector<std::string> overrides;
  options.addOptions(app);
  auto* scenario_opt = app.add_option(
      "--scenario", scenario_file,
      "scenario file (deploy/scenarios/*.yaml): robot, start pose, wall and substep rate (rates.drive_hz) come "
      "from it; excludes --robot, --x-m, --y-m, --yaw-deg, --wall, --substep-hz, --hold-s");
  app.add_option("--set", overrides, "override a scenario key, e.g. --set start.x_m=2 (repeatable)")
      ->needs(scenario_opt);
  const std::vector<CLI::Option*> scenario_keys{
      app.add_option("--robot", robot_file, "robot description (deploy/robots/*.yaml)"),
      app.add_option("--x-m", x_m, "start position of the robot centre on the wall, W's x [m]"),
      app.add_option("--y-m", y_m, "start position of the robot centre on the wall, W's y [m]"),
      app.add_option("--yaw-deg", yaw_deg, "start heading: angle of R's x from W's x [deg]"),
      app.add_option("--wall", wall_text, "vertical, floor, ceiling or overhang:DEG (degrees beyond vertical)"),
      app.add_option("--substep-hz", substep_hz, "integration rate of the model [Hz], 100..100000"),
      app.add_option("--hold-s", hold_s, "the chassis is held at its start pose until this time [s]")};
  for (auto* option : scenario_keys) option->excludes(scenario_opt);
  app.add_option("--inputs", inputs_list,
                 "inputs to read, comma-separated from command,adhesion, or none; an absent one keeps its "
                 "default (standing still; --downforce at the centre)");
  app.add_option("--downforce", downforce_n,
                 "adhesion force until thermo/AdhesionForce arrives, or for the whole run without it [N] "
                 "(default: 0 until it arrives, as thermo's initial state; without the adhesion input the "
                 "robot's adhesion.desired_downforce_n)");
  app.add_option("--contact", contact_text,
                 "force backend: direct (the model's own forces from Simbody's kinematics, the default) or simbody "
                 "(Simbody's contact subsystem and force elements: the same physics, slower; the reference)");
  return guardedMain(app, argc, argv, "drive", [&]() -> int {
    initLogging(options.name);
    const auto which = drive::parseDriveNodeInputs(inputs_list);
    auto wall = drive::WallOrientation::parse("--wall", wall_text);
    if (!scenario_file.empty()) {
      const Scenario scenario = loadScenario(scenario_file, overrides);
      robot_file = scenario.robotPath();
      x_m = scenario.start.x_m;
      y_m = scenario.start.y_m;
      yaw_deg = scenario.start.yaw_deg;
      wall = wallFromScenario(scenario.wall);
      substep_hz = scenario.rates.drive_hz;
      hold_s = scenario.start.hold_s;
      end_on_fall = scenario.end_on.fall;
      scene_file = scenario.scenePath(CLIMBSIM_BUILD_DIR);
      spdlog::info("drive: scenario {}: start x = {} m, y = {} m, yaw = {} deg; wall {} (overhang {} deg); {} Hz "
                   "substeps",
                   scenario.name, x_m, y_m, yaw_deg, toString(scenario.wall.kind), scenario.wall.overhang_deg,
                   substep_hz);
    }
    if (!(std::isfinite(substep_hz) && substep_hz >= 100.0 && substep_hz <= 100000.0)) {
      throw ConfigError("--substep-hz = " + std::to_string(substep_hz) + ": must be in [100, 100000]");
    }
    for (const auto& [name, value] : {std::pair{"--x-m", x_m}, {"--y-m", y_m}, {"--yaw-deg", yaw_deg}}) {
      if (!std::isfinite(value)) throw ConfigError(std::string(name) + " = " + std::to_string(value) + ": must be finite");
    }
    const RobotDescription robot = loadRobotDescription(robot_file);
    const RobotGeometry geometry = computeGeometry(robot);
    drive::DriveParams params = drive::driveParamsFromRobot(robot, geometry);
    params.substep_s = 1.0 / substep_hz;
    params.contact_backend = drive::parseContactBackend("--contact", contact_text);
    spdlog::info("drive: force backend {}", drive::toString(params.contact_backend));
    // With thermo's AdhesionForce as an input, its initial state (ambient chambers, F = 0)
    // holds until its first sample; without it, the desired downforce for the whole run.
    if (std::isnan(downforce_n)) {
      downforce_n = which.adhesion ? drive::kAdhesionForceBeforeThermo_n : robot.adhesion.desired_downforce_n;
    }
    drive::DriveNode node(params, wall, drive::StartPose{x_m, y_m, yaw_deg * 3.14159265358979323846 / 180.0},
                          downforce_n);
    if (!(std::isfinite(hold_s) && hold_s >= 0.0)) {
      throw ConfigError("--hold-s = " + std::to_string(hold_s) + ": must be finite and >= 0");
    }
    node.holdUntil(std::llround(hold_s * 1e9));

    // Loaded while the participant joins the run: ready by step 0.
    std::future<std::optional<drive::WheelsOverScene>> wheel_check_loading;
    if (!scene_file.empty()) wheel_check_loading = std::async(std::launch::async, wheelCheck, scene_file, params.wheels);
    std::optional<drive::WheelsOverScene> wheel_check;

    LockstepParticipant participant(options);
    auto* commands =
        which.command ? &participant.input<DriveCommandPubSubType>(drive::topic::kDriveCommand) : nullptr;
    auto* adhesion =
        which.adhesion ? &participant.input<AdhesionForcePubSubType>(drive::topic::kAdhesionForce) : nullptr;
    auto& robot_state = participant.output<RobotStatePubSubType>(drive::topic::kRobotState);
    auto& drive_state = participant.output<DriveStatePubSubType>(drive::topic::kDriveState);
    const std::int64_t period = participant.schedule().period_steps;
    {  // The state before step 0 (the start pose at rest): the trace's row 0.
      auto state_sample = drive::robotStateToIdl(node.initialOutputs());
      robot_state.recordInitial(state_sample);
      auto wheels_sample = drive::driveStateToIdl(node.initialOutputs());
      drive_state.recordInitial(wheels_sample);
    }
    bool fell_reported = false;

    const int code = participant.run([&](const StepContext& ctx) {
      const auto command_samples = commands ? commands->get(ctx) : std::vector<DriveCommand>{};
      const auto adhesion_samples = adhesion ? adhesion->get(ctx) : std::vector<AdhesionForce>{};
      // The model advances by this participant's period, not by one clock step.
      const auto& outputs = node.step(ctx.t_ns, ctx.dt_ns * period, command_samples, adhesion_samples);
      auto state_sample = drive::robotStateToIdl(outputs);
      robot_state.write(ctx, state_sample);
      auto wheels_sample = drive::driveStateToIdl(outputs);
      drive_state.write(ctx, wheels_sample);
      if (wheel_check_loading.valid()) wheel_check = wheel_check_loading.get();
      if (wheel_check) {
        for (const std::size_t w : wheel_check->newlyOverNothing(outputs)) {
          // The launcher reads "wheel N stands over nothing at t = T s" into summary.json.
          spdlog::warn("drive: {}", wheel_check->overNothingText(outputs, w, ctx.t_ns + ctx.dt_ns * period));
        }
      }
      if (outputs.fell && !fell_reported) {
        fell_reported = true;
        const auto& p = outputs.position_m;
        char reason[200];
        const auto& v = outputs.linear_velocity_mps;
        std::snprintf(reason, sizeof(reason),
                      "FELL at t = %.3f s: the robot left the wall at x = %.3f m, y = %.3f m (%.3f m off the wall "
                      "plane, sliding at %.2f m/s)",
                      static_cast<double>(ctx.t_ns + ctx.dt_ns * period) * 1e-9, p[0], p[1], p[2],
                      std::hypot(v[0], v[1]));
        if (end_on_fall) {
          participant.reportFell(reason);  // the run ends once everyone has reached the frozen horizon
        } else {
          spdlog::warn("drive: {} (the run goes on: end_on.fall is false)", reason);
        }
      }
    });
    logDroppedSamples(node.droppedCommands() + node.droppedAdhesion(),
                      "commands " + std::to_string(node.droppedCommands()) + ", adhesion " +
                          std::to_string(node.droppedAdhesion()));
    return code;
  });
}
