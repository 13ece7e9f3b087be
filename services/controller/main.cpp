/// climbsim-controller: the scenario's controller (docs/design.md#models, docs/scenario-files.md).
/// Reads ChamberState and AdhesionForce; writes ValveCommand (unless the scenario's controller is
/// external), EngineCommand (engines on at full speed) and the scenario's DriveCommand schedule
/// every step.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <iostream>

#include "climbsim/lockstep_participant.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/topic_names.hpp"
#include "client_config.hpp"
#include "node/controller_node.hpp"
#include "robotPubSubTypes.h"
#include "thermoPubSubTypes.h"

#ifndef CLIMBSIM_DEFAULT_SCENARIO_FILE
#error "CLIMBSIM_DEFAULT_SCENARIO_FILE must name the default scenario"
#endif

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-controller: reference adhesion controller and drive-command schedule"};
  ParticipantOptions options;
  std::string scenario_file = CLIMBSIM_DEFAULT_SCENARIO_FILE;
  std::vector<std::string> overrides;
  options.addOptions(app);
  app.add_option("--scenario", scenario_file, "scenario file (deploy/scenarios/*.yaml)");
  app.add_option("--set", overrides, "override a scenario key, e.g. --set controller.type=fixed (repeatable)");
  bool print_config = false;
  app.add_flag("--print-config", print_config,
               "print the validated configuration as JSON and exit (the Python controller reads it)");
  return guardedMain(app, argc, argv, "controller", [&]() -> int {
    initLogging(options.name);
    const Scenario scenario = loadScenario(scenario_file, overrides);
    const RobotDescription robot = loadRobotDescription(scenario.robotPath());
    const RobotGeometry geometry = computeGeometry(robot);
    const controller::ControllerParams config = controller::controllerParams(scenario, robot, geometry);
    controller::ControllerNode node(config);  // validates the reference controller's params
    if (print_config) {
      std::cout << controller::clientConfigJson(scenario, config).dump(1) << std::endl;
      return 0;
    }
    spdlog::info("controller: {} controller, scenario {}", toString(scenario.controller.kind), scenario.name);

    LockstepParticipant participant(options);
    auto& states = participant.input<ChamberStatePubSubType>(topic::kChamberState);
    auto& forces = participant.input<AdhesionForcePubSubType>(topic::kAdhesionForce);
    auto* valves = node.commandsValves() ? &participant.output<ValveCommandPubSubType>(topic::kValveCommand) : nullptr;
    auto& engines = participant.output<EngineCommandPubSubType>(topic::kEngineCommand);
    auto& drive = participant.output<DriveCommandPubSubType>(topic::kDriveCommand);
    const std::int64_t period = participant.schedule().period_steps;

    const int code = participant.run([&](const StepContext& ctx) {
      auto commands = node.step(ctx.t_ns, ctx.dt_ns * period, states.get(ctx), forces.get(ctx));
      if (valves) valves->write(ctx, *commands.valves);
      engines.write(ctx, commands.engines);
      drive.write(ctx, commands.drive);
    });
    logDroppedSamples(node.droppedSamples(), "thermo samples");
    return code;
  });
}
