#include "thermo_participant.hpp"

#include <string>
#include <vector>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/run_stats.hpp"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"
#include "thermo_translate.hpp"

namespace climbsim::thermo {

int runThermoParticipant(const ParticipantOptions& options, const ThermoNodeInputs& which, ThermoNode& node) {
  LockstepParticipant participant(options);
  auto* leakage = which.leakage ? &participant.input<LeakagePubSubType>(topic::kLeakage) : nullptr;
  auto* valves = which.valves ? &participant.input<ValveCommandPubSubType>(topic::kValveCommand) : nullptr;
  auto* engines = which.engines ? &participant.input<EngineCommandPubSubType>(topic::kEngineCommand) : nullptr;
  auto& chamber_state = participant.output<ChamberStatePubSubType>(topic::kChamberState);
  auto& adhesion = participant.output<AdhesionForcePubSubType>(topic::kAdhesionForce);
  const std::int64_t period = participant.schedule().period_steps;
  {  // The state before step 0 (ambient): the trace's row 0.
    const auto initial = node.initialOutputs();
    auto state_sample = chamberStateToIdl(initial);
    chamber_state.recordInitial(state_sample);
    auto force_sample = adhesionForceToIdl(initial);
    adhesion.recordInitial(force_sample);
  }

  const int code = participant.run([&](const StepContext& ctx) {
    const auto leakage_parts = leakage ? leakage->get(ctx) : std::vector<climbsim::Leakage>{};
    const auto valve_samples = valves ? valves->get(ctx) : std::vector<climbsim::ValveCommand>{};
    const auto engine_samples = engines ? engines->get(ctx) : std::vector<climbsim::EngineCommand>{};
    // The model advances by this participant's period, not by one clock step.
    const auto outputs = node.step(ctx.t_ns, ctx.dt_ns * period, leakage_parts, valve_samples, engine_samples);
    auto state_sample = chamberStateToIdl(outputs);
    chamber_state.write(ctx, state_sample);
    auto force_sample = adhesionForceToIdl(outputs);
    force_sample.downforce_setpoint_n(node.downforceSetpoint());
    adhesion.write(ctx, force_sample);
  });
  logDroppedSamples(node.leakage().dropped() + node.droppedValveCommands() + node.droppedEngineCommands(),
                    "leakage " + std::to_string(node.leakage().dropped()) + ", valve commands " +
                        std::to_string(node.droppedValveCommands()) + ", engine commands " +
                        std::to_string(node.droppedEngineCommands()));
  leaveAfterResults(participant.name().c_str(), code);
  return code;
}

}  // namespace climbsim::thermo
