// The drive model's contract (Params, State, Inputs, Outputs, step(State&, Inputs, t, dt)):
// everything that evolves is in DriveModelState, so a saved copy steps exactly as the
// original, and any model built from the same params steps a state as the one that made it.
// Both force backends (the simbody one keeps contact and Measure variables in the SimTK::State).

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "drive_model.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;

DriveParams cromsci(ContactBackend backend) {
  const auto robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
  DriveParams params = driveParamsFromRobot(robot, computeGeometry(robot));
  params.contact_backend = backend;
  return params;
}

/// Inputs that exercise everything that has a state: a changing body command (dead time,
/// rate limit, wheel angle references), a changing downforce off-centre (friction deflections,
/// load shift), and a hold for the first 0.3 s.
DriveInputs inputsAt(std::int64_t t_ns) {
  const double t = static_cast<double>(t_ns) * 1e-9;
  DriveInputs in;
  in.held = t < 0.3;
  in.downforce_n = 1700.0 + 400.0 * std::sin(3.0 * t);
  in.pf_x_m = 0.02 * std::cos(t);
  in.pf_y_m = -0.01;
  in.command.vx_mps = t < 0.6 ? 0.05 : -0.03;
  in.command.vy_mps = 0.02 * std::sin(t);
  in.command.wz_radps = t < 0.8 ? 0.1 : -0.05;
  return in;
}

/// Another set of inputs, for a copy that goes its own way.
DriveInputs otherInputsAt(std::int64_t t_ns) {
  DriveInputs in = inputsAt(t_ns);
  in.downforce_n = 900.0;
  in.command.vy_mps = -0.05;
  return in;
}

/// Every field of `a` and `b` equal bit for bit.
::testing::AssertionResult sameBits(const DriveOutputs& a, const DriveOutputs& b) {
  const auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
  if (a.t_ns != b.t_ns) return ::testing::AssertionFailure() << "t_ns " << a.t_ns << " vs " << b.t_ns;
  if (!same(a.position_m, b.position_m) || !same(a.orientation_wxyz, b.orientation_wxyz) ||
      !same(a.linear_velocity_mps, b.linear_velocity_mps) || !same(a.angular_velocity_radps, b.angular_velocity_radps)) {
    return ::testing::AssertionFailure() << "pose or twist differ at t = " << a.t_ns << " ns: x " << a.position_m[0]
                                         << " vs " << b.position_m[0];
  }
  if (a.wheels.size() != b.wheels.size() || a.fell != b.fell) return ::testing::AssertionFailure() << "wheels or fell";
  for (std::size_t i = 0; i < a.wheels.size(); ++i) {
    if (!same(a.wheels[i], b.wheels[i])) {
      return ::testing::AssertionFailure() << "wheel " << i << " differs at t = " << a.t_ns << " ns: N "
                                           << a.wheels[i].normal_force_n << " vs " << b.wheels[i].normal_force_n;
    }
  }
  return ::testing::AssertionSuccess();
}

/// Steps `state` with `model` over [from, to) with `inputs`; the outputs of every step.
template <class Inputs>
std::vector<DriveOutputs> advance(const DriveModel& model, DriveModelState& state, std::int64_t from, std::int64_t to,
                                  const Inputs& inputs) {
  std::vector<DriveOutputs> out;
  for (std::int64_t t = from; t < to; t += kStepNs) out.push_back(model.step(state, inputs(t), t, kStepNs));
  return out;
}

class DriveState : public ::testing::TestWithParam<ContactBackend> {};

TEST_P(DriveState, ACopySteppedWithTheSameInputsGivesTheSameOutputsBitForBit) {
  const DriveModel model(cromsci(GetParam()), WallOrientation::vertical());
  DriveModelState original = model.initialState(StartPose{0.2, 0.4, 0.1});
  advance(model, original, 0, 500'000'000, inputsAt);  // mid-hold release, commands in the dead time
  DriveModelState copy = original;                      // copy construction
  DriveModelState assigned = model.initialState(StartPose{});
  assigned = original;                                   // copy assignment over another state
  ASSERT_EQ(copy.t_ns(), original.t_ns());
  ASSERT_TRUE(sameBits(copy.outputs(), original.outputs()));

  const auto a = advance(model, original, 500'000'000, 1'200'000'000, inputsAt);
  const auto b = advance(model, copy, 500'000'000, 1'200'000'000, inputsAt);
  const auto c = advance(model, assigned, 500'000'000, 1'200'000'000, inputsAt);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_TRUE(sameBits(a[k], b[k])) << "copy, step " << k;
    ASSERT_TRUE(sameBits(a[k], c[k])) << "assigned, step " << k;
  }
  EXPECT_EQ(copy.substeps(), original.substeps());
  // The robot really moved and the wheels really carried load: not a trivially equal run.
  EXPECT_GT(std::hypot(a.back().position_m[0] - 0.2, a.back().position_m[1] - 0.4), 1e-3);
  EXPECT_GT(a.back().wheels[0].normal_force_n, 100.0);
}

TEST_P(DriveState, ACopyGoingItsOwnWayLeavesTheOriginalUntouched) {
  const DriveModel model(cromsci(GetParam()), WallOrientation::vertical());
  // Reference: one state stepped straight through.
  DriveModelState straight = model.initialState(StartPose{});
  const auto reference = advance(model, straight, 0, 1'000'000'000, inputsAt);

  // Same run, but at 0.4 s a copy is stepped with other inputs, interleaved step by step
  // with the original: nothing of the copy's steps may leak into the original's.
  DriveModelState original = model.initialState(StartPose{});
  advance(model, original, 0, 400'000'000, inputsAt);
  DriveModelState branch = original;
  std::vector<DriveOutputs> original_out, branch_out;
  for (std::int64_t t = 400'000'000; t < 1'000'000'000; t += kStepNs) {
    branch_out.push_back(model.step(branch, otherInputsAt(t), t, kStepNs));
    original_out.push_back(model.step(original, inputsAt(t), t, kStepNs));
  }
  const std::size_t offset = 400'000'000 / kStepNs;
  for (std::size_t k = 0; k < original_out.size(); ++k) {
    ASSERT_TRUE(sameBits(original_out[k], reference[offset + k])) << "step " << k;
  }
  // The branch did go elsewhere: other inputs, other outputs.
  EXPECT_NE(branch_out.back().wheels[0].normal_force_n, original_out.back().wheels[0].normal_force_n);
}

TEST_P(DriveState, TwoModelsOfTheSameParamsStepAStateAlike) {
  const DriveParams params = cromsci(GetParam());
  const DriveModel first(params, WallOrientation::vertical());
  const DriveModel second(params, WallOrientation::vertical());
  DriveModelState one = first.initialState(StartPose{});
  const auto reference = advance(first, one, 0, 900'000'000, inputsAt);

  // The state made by the second model, stepped by both in turn.
  DriveModelState alternating = second.initialState(StartPose{});
  for (std::int64_t t = 0, k = 0; t < 900'000'000; t += kStepNs, ++k) {
    const DriveModel& model = k % 2 == 0 ? second : first;
    ASSERT_TRUE(sameBits(model.step(alternating, inputsAt(t), t, kStepNs), reference[static_cast<std::size_t>(k)]))
        << "step " << k;
  }
  // A state of the first model handed to the second half way.
  DriveModelState handed = first.initialState(StartPose{});
  advance(first, handed, 0, 450'000'000, inputsAt);
  const auto rest = advance(second, handed, 450'000'000, 900'000'000, inputsAt);
  const std::size_t offset = 450'000'000 / kStepNs;
  for (std::size_t k = 0; k < rest.size(); ++k) ASSERT_TRUE(sameBits(rest[k], reference[offset + k])) << "step " << k;
}

INSTANTIATE_TEST_SUITE_P(Backends, DriveState, ::testing::Values(ContactBackend::kDirect, ContactBackend::kSimbody),
                         [](const auto& info) { return std::string(toString(info.param)); });

TEST(DriveStateShape, AStateOfAModelOfAnotherShapeIsRefused) {
  const DriveModel direct(cromsci(ContactBackend::kDirect), WallOrientation::vertical());
  const DriveModel simbody(cromsci(ContactBackend::kSimbody), WallOrientation::vertical());
  DriveParams four = cromsci(ContactBackend::kDirect);
  four.wheels.push_back(WheelMount{0.0, -0.3});
  const DriveModel four_wheels(four, WallOrientation::vertical());
  DriveModelState state = direct.initialState(StartPose{});
  EXPECT_THROW(simbody.step(state, inputsAt(0), 0, kStepNs), std::invalid_argument);
  EXPECT_THROW(four_wheels.step(state, inputsAt(0), 0, kStepNs), std::invalid_argument);
  EXPECT_NO_THROW(direct.step(state, inputsAt(0), 0, kStepNs));
}

}  // namespace
}  // namespace climbsim::drive
