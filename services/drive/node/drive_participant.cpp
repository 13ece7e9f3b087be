#include "drive_participant.hpp"

#include <spdlog/spdlog.h>

#include <future>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/run_stats.hpp"
#include "drive_translate.hpp"
#include "fall_report.hpp"
#include "robotPubSubTypes.h"
#include "thermoPubSubTypes.h"
#include "wheels_over_scene.hpp"

namespace climbsim::drive {
int runDriveParticipant(const ParticipantOptions& options, const DriveSetup& setup, DriveNode& node) {
  // Loaded while the participant joins the run: ready by step 0.
  std::future<std::optional<WheelsOverScene>> wheel_check_loading;
  if (setup.wheel_scene.valid()) {
    wheel_check_loading = std::async(std::launch::async, [&setup] {
      return wheelCheckOnScene(setup.wheel_scene, setup.params.wheels);
    });
  }
  std::optional<WheelsOverScene> wheel_check;

  LockstepParticipant participant(options);
  auto* commands =
      setup.inputs.command ? &participant.input<DriveCommandPubSubType>(topic::kDriveCommand) : nullptr;
  auto* adhesion =
      setup.inputs.adhesion ? &participant.input<AdhesionForcePubSubType>(topic::kAdhesionForce) : nullptr;
  auto& robot_state = participant.output<RobotStatePubSubType>(topic::kRobotState);
  auto& drive_state = participant.output<DriveStatePubSubType>(topic::kDriveState);
  const std::int64_t period = participant.schedule().period_steps;
  {  // The state before step 0 (the start pose at rest): the trace's row 0.
    auto state_sample = robotStateToIdl(node.initialOutputs());
    robot_state.recordInitial(state_sample);
    auto wheels_sample = driveStateToIdl(node.initialOutputs());
    drive_state.recordInitial(wheels_sample);
  }
  bool fell_reported = false;
  climbsim::DriveState wheels_sample;  // kept from step to step: filled in place

  const int code = participant.run([&](const StepContext& ctx) {
    const auto command_samples = commands ? commands->get(ctx) : std::vector<climbsim::DriveCommand>{};
    const auto adhesion_samples = adhesion ? adhesion->get(ctx) : std::vector<climbsim::AdhesionForce>{};
    // The model advances by this participant's period, not by one clock step.
    const auto& outputs = node.step(ctx.t_ns, ctx.dt_ns * period, command_samples, adhesion_samples);
    auto state_sample = robotStateToIdl(outputs);
    robot_state.write(ctx, state_sample);
    driveStateToIdl(outputs, wheels_sample);
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
      const std::string reason = fellReason(outputs, ctx.t_ns + ctx.dt_ns * period);
      if (setup.end_on_fall) {
        participant.reportFell(reason);  // the run ends once everyone has reached the frozen horizon
      } else {
        spdlog::warn("drive: {} (the run goes on: end_on.fall is false)", reason);
      }
    }
  });
  logDroppedSamples(node.droppedCommands() + node.droppedAdhesion(),
                    "commands " + std::to_string(node.droppedCommands()) + ", adhesion " +
                        std::to_string(node.droppedAdhesion()));
  leaveAfterResults(participant.name().c_str(), code);
  return code;
}

}  // namespace climbsim::drive
