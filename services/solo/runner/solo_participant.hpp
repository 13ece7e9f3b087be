#pragma once
/// @file
/// The one stepper of climbsim solo: every model of the composition is stepped through
/// SoloParticipant, behind its service's node, as the lockstep steps it in a distributed run
/// (docs/design.md#the-model-contract, docs/design.md#multi-rate-schedules).
///
/// A node of a service holds its model (a model of the contract: `typename Node::Model`,
/// climbsim::is_model_v) and the model's state, and steps in the lockstep's shape:
/// `node.step(t_ns, dt_ns, samples...)`, one vector of samples per input topic, dt_ns the
/// participant's period. The participant reads those samples from the topics at the stamps the
/// lockstep gives (one-step lag: StampedTopic), steps the node when its schedule is due and
/// hands the node's outputs to the caller, who writes them to the topics.

#include <cstdint>
#include <string>
#include <utility>

#include "climbsim/model_contract.hpp"
#include "climbsim/schedule.hpp"
#include "stamped_bus.hpp"

namespace climbsim::solo {

template <class Node>
class SoloParticipant {
  static_assert(is_model_v<typename Node::Model>, "a node steps a model of the contract (model_contract.hpp)");

 public:
  /// `node` (which must outlive this) runs as participant `name` on `schedule` (validated:
  /// ConfigError naming `name`).
  SoloParticipant(std::string name, const Schedule& schedule, Node& node)
      : name_(std::move(name)), schedule_(schedule), node_(node) {
    schedule_.validate(name_);
  }

  /// Step k at clock time t_ns of a clock step dt_ns [ns]: when due, steps the node over
  /// [t_ns, t_ns + dt_ns * period) with the samples `inputs` hold for it (Lag::kOneStep) and
  /// calls `publish` with what the node's step returns. Returns whether it was due.
  template <class Publish, class... Samples>
  bool step(std::uint64_t k, std::int64_t t_ns, std::int64_t dt_ns, const Publish& publish,
            const StampedTopic<Samples>&... inputs) {
    if (!schedule_.isDue(k)) return false;
    const std::int64_t period_ns = dt_ns * static_cast<std::int64_t>(schedule_.period_steps);
    publish(node_.step(t_ns, period_ns, inputs.get(k, Lag::kOneStep)...));
    return true;
  }

  const std::string& name() const { return name_; }
  const Schedule& schedule() const { return schedule_; }

 private:
  std::string name_;
  Schedule schedule_;
  Node& node_;
};

}  // namespace climbsim::solo
