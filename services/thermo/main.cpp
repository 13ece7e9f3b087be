/// climbsim-thermo: the airflow and downforce service (docs/design.md#airflow-and-downforce). Reads
/// Leakage (merged from every sealing shard), ValveCommand and EngineCommand; writes ChamberState
/// and AdhesionForce every due step. With --scenario the robot and the plant faults (stuck
/// valve, failed engine) come from the scenario file.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <optional>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "node/thermo_node.hpp"
#include "node/thermo_translate.hpp"
#include "params_from_robot.hpp"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-thermo: chambers, reservoir, suction engines, valves and downforce"};
  ParticipantOptions options;
  std::string robot_file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  std::string inputs_list = "leakage,valves,engines";
  std::string scenario_file;
  std::vector<std::string> overrides;
  options.addOptions(app);
  auto* robot_opt = app.add_option("--robot", robot_file, "robot description (deploy/robots/*.yaml)");
  auto* scenario_opt =
      app.add_option("--scenario", scenario_file,
                     "scenario file (deploy/scenarios/*.yaml): the robot and the plant faults (valve_stuck, "
                     "engine_failure) come from it; excludes --robot");
  app.add_option("--set", overrides, "override a scenario key, e.g. --set faults[0].t_s=3 (repeatable)")
      ->needs(scenario_opt);
  robot_opt->excludes(scenario_opt);
  app.add_option("--inputs", inputs_list,
                 "inputs to read, comma-separated from leakage,valves,engines, or none; "
                 "an absent one keeps its default (basic leakage, valves closed, engines off)");
  return guardedMain(app, argc, argv, "thermo", [&]() -> int {
    initLogging(options.name);
    const auto which = thermo::parseThermoNodeInputs(inputs_list);
    std::optional<Scenario> scenario;
    if (!scenario_file.empty()) {
      scenario = loadScenario(scenario_file, overrides);
      robot_file = scenario->robotPath();
    }
    const RobotDescription robot = loadRobotDescription(robot_file);
    const RobotGeometry geometry = computeGeometry(robot);
    thermo::ThermoParams params = thermo::thermoParamsFromRobot(robot, geometry);
    if (scenario) params.faults = thermo::plantFaultsFromScenario(scenario->faults, scenario->source, params.engines.size());
    thermo::ThermoNode node(std::move(params), thermo::segmentNames(geometry), thermo::basicLeakAreas(robot, geometry));
    if (scenario) spdlog::info("thermo: scenario {}: {} plant fault(s)", scenario->name, scenario->faults.size());

    LockstepParticipant participant(options);
    auto* leakage = which.leakage ? &participant.input<LeakagePubSubType>(thermo::topic::kLeakage) : nullptr;
    auto* valves = which.valves ? &participant.input<ValveCommandPubSubType>(thermo::topic::kValveCommand) : nullptr;
    auto* engines =
        which.engines ? &participant.input<EngineCommandPubSubType>(thermo::topic::kEngineCommand) : nullptr;
    auto& chamber_state = participant.output<ChamberStatePubSubType>(thermo::topic::kChamberState);
    auto& adhesion = participant.output<AdhesionForcePubSubType>(thermo::topic::kAdhesionForce);
    const std::int64_t period = participant.schedule().period_steps;
    {  // The state before step 0 (ambient): the trace's row 0.
      const auto initial = node.initialOutputs();
      auto state_sample = thermo::chamberStateToIdl(initial);
      chamber_state.recordInitial(state_sample);
      auto force_sample = thermo::adhesionForceToIdl(initial);
      adhesion.recordInitial(force_sample);
    }

    const int code = participant.run([&](const StepContext& ctx) {
      const auto leakage_parts = leakage ? leakage->get(ctx) : std::vector<Leakage>{};
      const auto valve_samples = valves ? valves->get(ctx) : std::vector<ValveCommand>{};
      const auto engine_samples = engines ? engines->get(ctx) : std::vector<EngineCommand>{};
      // The model advances by this participant's period, not by one clock step.
      const auto outputs = node.step(ctx.t_ns, ctx.dt_ns * period, leakage_parts, valve_samples, engine_samples);
      auto state_sample = thermo::chamberStateToIdl(outputs);
      chamber_state.write(ctx, state_sample);
      auto force_sample = thermo::adhesionForceToIdl(outputs);
      force_sample.downforce_setpoint_n(node.downforceSetpoint());
      adhesion.write(ctx, force_sample);
    });
    logDroppedSamples(node.leakage().dropped() + node.droppedValveCommands() + node.droppedEngineCommands(),
                      "leakage " + std::to_string(node.leakage().dropped()) + ", valve commands " +
                          std::to_string(node.droppedValveCommands()) + ", engine commands " +
                          std::to_string(node.droppedEngineCommands()));
    return code;
  });
}
