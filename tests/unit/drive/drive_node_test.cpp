// The drive node without a network: translators, dropping and counting bad samples.

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "climbsim/errors.hpp"
#include "drive_node.hpp"
#include "drive_translate.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;

DriveParams shipped(const std::string& name) {
  const auto robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml");
  return driveParamsFromRobot(robot, computeGeometry(robot));
}

DriveParams cromsci() { return shipped("cromsci"); }

climbsim::DriveCommand bodyCommand(double vx, const char* source = "controller") {
  DriveCommand c;
  c.vx_mps = vx;
  auto s = driveCommandToIdl(c);
  s.source(source);
  return s;
}

TEST(DriveTranslate, CommandsAndOutputsSurviveTheRoundTrip) {
  DriveCommand c;
  c.steering_rad = {0.1, 0.2, 0.3};
  c.wheel_speed_radps = {1.0, -1.0, 0.5};
  const auto back = driveCommandFromIdl(driveCommandToIdl(c));
  EXPECT_EQ(back.steering_rad, c.steering_rad);
  EXPECT_EQ(back.wheel_speed_radps, c.wheel_speed_radps);
  DriveOutputs o;
  o.position_m = {1, 2, 3};
  o.orientation_wxyz = {0, 1, 0, 0};
  o.wheels.resize(3);
  o.wheels[2].normal_force_n = 700.0;
  o.fell = true;
  const auto rs = robotStateToIdl(o);
  EXPECT_EQ(rs.position_m()[2], 3.0);
  EXPECT_EQ(rs.orientation_wxyz()[1], 1.0);
  EXPECT_TRUE(rs.fell());
  const auto ds = driveStateToIdl(o);
  ASSERT_EQ(ds.wheels().size(), 3u);
  EXPECT_EQ(ds.wheels()[2].normal_force_n(), 700.0);
}

TEST(DriveNode, BadSamplesAreDroppedCountedAndTheLastValidOneHeld) {
  DriveNode node(cromsci(), WallOrientation::vertical(), StartPose{}, 2200.0);
  node.step(0, kStepNs, {bodyCommand(0.05)}, {});
  EXPECT_EQ(node.heldInputs().command.vx_mps, 0.05);
  node.step(kStepNs, kStepNs, {bodyCommand(std::numeric_limits<double>::quiet_NaN()), bodyCommand(1e3)}, {});
  EXPECT_EQ(node.droppedCommands(), 2u);
  EXPECT_EQ(node.heldInputs().command.vx_mps, 0.05);
  auto bad_force = adhesionForceToIdl(std::numeric_limits<double>::infinity(), 0.0, 0.0);
  auto far_point = adhesionForceToIdl(2000.0, 5.0, 0.0);
  node.step(2 * kStepNs, kStepNs, {}, {bad_force, far_point, adhesionForceToIdl(1800.0, 0.01, 0.0)});
  EXPECT_EQ(node.droppedAdhesion(), 2u);
  EXPECT_EQ(node.heldInputs().downforce_n, 1800.0);
  EXPECT_EQ(node.heldInputs().pf_x_m, 0.01);
}

/// Everything spdlog's default logger writes while it lives.
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    spdlog::set_default_logger(
        std::make_shared<spdlog::logger>("capture", std::make_shared<spdlog::sinks::ostream_sink_st>(text_)));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  std::string text() const { return text_.str(); }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> previous_;
};

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(DriveNode, ASidewaysSpeedFixedWheelsCannotGiveIsAppliedAndSaidOnce) {
  LogCapture log;
  DriveNode node(shipped("single-chamber"), WallOrientation::vertical(), StartPose{}, 700.0);
  auto sideways = bodyCommand(0.02);
  sideways.vy_mps(0.03);
  for (std::int64_t k = 0; k < 3; ++k) node.step(k * kStepNs, kStepNs, {sideways}, {});
  EXPECT_EQ(node.droppedCommands(), 0u);
  EXPECT_EQ(node.heldInputs().command.vy_mps, 0.03);
  EXPECT_EQ(count(log.text(), "cannot move sideways"), 1u) << log.text();
  EXPECT_NE(log.text().find("fixed wheels (1, 2)"), std::string::npos) << log.text();
  // A robot whose wheels all steer takes vy without a word.
  DriveNode steered(cromsci(), WallOrientation::vertical(), StartPose{}, 2200.0);
  steered.step(0, kStepNs, {sideways}, {});
  EXPECT_EQ(count(log.text(), "cannot move sideways"), 1u) << log.text();
}

TEST(DriveNode, InputListsAndDefaultsAreChecked) {
  EXPECT_FALSE(parseDriveNodeInputs("none").command);
  EXPECT_TRUE(parseDriveNodeInputs("adhesion").adhesion);
  EXPECT_FALSE(parseDriveNodeInputs("adhesion").command);
  EXPECT_THROW(parseDriveNodeInputs("command,valves"), ConfigError);
  EXPECT_THROW(DriveNode(cromsci(), WallOrientation::vertical(), StartPose{}, std::nan("")), ConfigError);
}

}  // namespace
}  // namespace climbsim::drive
