// climbsim solo's one stepper (services/solo/runner/solo_participant.hpp): a node of a model of
// the contract is stepped when its schedule is due, over its period, with the samples its input
// topics hold for it at the lockstep's stamps; its outputs go to the caller.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/model_contract.hpp"
#include "robot.h"
#include "runner/solo_participant.hpp"

namespace climbsim::solo {
namespace {

/// A model that counts its steps and sums the forward speeds of its inputs.
struct CountingModel {
  struct Params {};
  struct State {
    int steps = 0;
  };
  struct Inputs {
    double vx_sum = 0.0;
  };
  struct Outputs {
    int steps = 0;
    double vx_sum = 0.0;
    std::int64_t t_ns = 0, dt_ns = 0;
  };
  Outputs step(State& state, const Inputs& in, std::int64_t t_ns, std::int64_t dt_ns) const {
    return Outputs{++state.steps, in.vx_sum, t_ns, dt_ns};
  }
};
static_assert(is_model_v<CountingModel>);

/// Its node: DriveCommand samples in.
struct CountingNode {
  using Model = CountingModel;
  Model model;
  Model::State state;
  Model::Outputs step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::DriveCommand>& commands) {
    Model::Inputs in;
    for (const auto& c : commands) in.vx_sum += c.vx_mps();
    return model.step(state, in, t_ns, dt_ns);
  }
};

TEST(SoloParticipant, StepsWhenDueOverItsPeriodWithTheSamplesOfTheLastDueStampBefore) {
  StampedTopic<climbsim::DriveCommand> commands("commands");
  commands.addProducer("controller", Schedule{1, 0});
  CountingNode node;
  SoloParticipant participant("counter", Schedule{2, 1}, node);  // due at 1, 3, 5, ...
  std::vector<CountingModel::Outputs> seen;
  const auto publish = [&](const CountingModel::Outputs& out) { seen.push_back(out); };
  const std::int64_t dt_ns = 5'000'000;
  for (std::uint64_t k = 0; k < 4; ++k) {
    const std::int64_t t_ns = static_cast<std::int64_t>(k) * dt_ns;
    climbsim::DriveCommand sample;
    sample.vx_mps(static_cast<double>(k + 1));
    commands.write("controller", k, t_ns, sample);
    EXPECT_EQ(participant.step(k, t_ns, dt_ns, publish, commands), k % 2 == 1) << "k = " << k;
  }
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].steps, 1);
  EXPECT_EQ(seen[0].vx_sum, 1.0) << "step 1 reads the controller's stamp 0";
  EXPECT_EQ(seen[0].t_ns, dt_ns);
  EXPECT_EQ(seen[0].dt_ns, 2 * dt_ns) << "the model advances by the participant's period";
  EXPECT_EQ(seen[1].steps, 2);
  EXPECT_EQ(seen[1].vx_sum, 3.0) << "step 3 reads stamp 2";
  EXPECT_EQ(node.state.steps, 2) << "the state lives in the node, stepped in place";
}

TEST(SoloParticipant, ABadScheduleIsNamed) {
  CountingNode node;
  EXPECT_THROW(SoloParticipant("counter", Schedule{2, 2}, node), ConfigError);
}

}  // namespace
}  // namespace climbsim::solo
