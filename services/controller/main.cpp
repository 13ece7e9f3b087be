/// climbsim-controller: the scenario's controller (docs/design.md#models, docs/scenario-files.md).
/// Reads ChamberState and AdhesionForce; writes ValveCommand (unless the scenario's controller is
/// external), EngineCommand (engines on at full speed, or at the engine law's speeds; not for
/// external on a robot without a reservoir) and the scenario's DriveCommand schedule every step. The scenario and robot map to its parameters in configure.hpp.

#include <spdlog/spdlog.h>

#include <iostream>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/service_command_line.hpp"
#include "climbsim/topic_names.hpp"
#include "client_config.hpp"
#include "configure.hpp"
#include "node/controller_node.hpp"
#include "robotPubSubTypes.h"
#include "thermoPubSubTypes.h"

#ifndef CLIMBSIM_DEFAULT_SCENARIO_FILE
#error "CLIMBSIM_DEFAULT_SCENARIO_FILE must name the default scenario"
#endif

int main(int argc, char** argv) {
  using namespace climbsim;
  ServiceCommandLine cli("climbsim-controller: reference adhesion controller and drive-command schedule",
                         "scenario file (deploy/scenarios/*.yaml)", "controller.type=fixed",
                         CLIMBSIM_DEFAULT_SCENARIO_FILE);
  bool print_config = false;
  cli.app.add_flag("--print-config", print_config,
                   "print the validated configuration as JSON and exit (the Python controller reads it)");
  return cli.run(argc, argv, "controller", [&]() -> int {
    initLogging(cli.participant.name);
    const ScenarioAndRobot run = cli.load();
    const controller::ControllerParams config = controller::configureController(run);
    controller::ControllerNode node(config);  // validates the reference controller's params
    if (print_config) {
      std::cout << controller::clientConfigJson(*run.scenario, config).dump(1) << std::endl;
      return 0;
    }
    spdlog::info("controller: {} controller, scenario {}", toString(run.scenario->controller.kind), run.scenario->name);

    LockstepParticipant participant(cli.participant);
    auto& states = participant.input<ChamberStatePubSubType>(topic::kChamberState);
    auto& forces = participant.input<AdhesionForcePubSubType>(topic::kAdhesionForce);
    auto* valves = node.commandsValves() ? &participant.output<ValveCommandPubSubType>(topic::kValveCommand) : nullptr;
    auto* engines = node.commandsEngines() ? &participant.output<EngineCommandPubSubType>(topic::kEngineCommand) : nullptr;
    auto& drive = participant.output<DriveCommandPubSubType>(topic::kDriveCommand);
    const std::int64_t period = participant.schedule().period_steps;

    const int code = participant.run([&](const StepContext& ctx) {
      auto commands = node.step(ctx.t_ns, ctx.dt_ns * period, states.get(ctx), forces.get(ctx));
      if (valves) valves->write(ctx, *commands.valves);
      if (engines) engines->write(ctx, *commands.engines);
      drive.write(ctx, commands.drive);
    });
    logDroppedSamples(node.droppedSamples(), "thermo samples");
    leaveAfterResults(participant.name().c_str(), code);
    return code;
  });
}
