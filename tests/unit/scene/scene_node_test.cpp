// The scene node without a network: translators, pose holding, depth heights against the
// known geometry of a wall with a step, the robot never in its own depth image.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include "climbsim/errors.hpp"
#include "scene_node.hpp"
#include "scene_test_files.hpp"
#include "scene_translate.hpp"

namespace climbsim::scene {
namespace {

constexpr double kStepHeight_m = 0.012;  ///< the wall's step at x_W = 0.3 m
constexpr double kStepX_m = 0.3;

/// Wall surface height z_W at x_W: 0 left of the step, kStepHeight_m right of it.
double wallHeight(double x_W) { return x_W < kStepX_m ? 0.0 : kStepHeight_m; }

/// A wall 4 m x 4 m in W (z_W = 0 for x < 0.3 m, 12 mm higher beyond), W placed like the
/// default pylon (6 m up, rolled 90 degrees), a robot body 0.3 m square 3 cm above its
/// sealing plane and a laser on a TCP.
std::string stepScene(const testing::TempDir& dir) {
  const double h = kStepHeight_m;
  const std::string s = std::to_string(kStepX_m);
  dir.write("wall.obj", "v -2 -2 0\nv " + s + " -2 0\nv " + s + " 2 0\nv -2 2 0\n"
                        "v " + s + " -2 " + std::to_string(h) + "\nv 2 -2 " + std::to_string(h) + "\nv 2 2 " +
                        std::to_string(h) + "\nv " + s + " 2 " + std::to_string(h) + "\n"
                        "v " + s + " -2 0\nv " + s + " 2 0\n"
                        "f 1 2 3\nf 1 3 4\nf 5 6 7\nf 5 7 8\nf 9 5 8\nf 9 8 10\n");
  dir.write("body.ply", testing::asPly(testing::square(0.3, 0.03)));
  return dir.write("step.xml", testing::sceneXml(R"(
  <part name="WALL" attached_to="ROOT" offset="0 0 6 90 0 0"/>
  <part name="CONCRETE" file="wall.obj" attached_to="WALL"/>
  <part name="ROBOT" file="body.ply" attached_to="WALL"/>
  <part name="TCP" attached_to="ROBOT" offset="0 0 0.35 0 0 0"/>
  <element name="robot_pose" type="3d Pose" angle_type="rad" attached_to="ROBOT"/>
  <distance_sensor name="laser_scanner" max_distance="4" scan_angle_range="240" angular_resolution="0.352423"
     offset="0 0 0 0 20 0" attached_to="TCP"/>
  <camera name="depth_cam" type="orthographic" near_limit="-0.05" far_limit="0.05" width="64" height="64"
     size="0.4 0.4" attached_to="ROBOT"/>
)"));
}

climbsim::RobotState stateAt(double x, double y, double z, double yaw) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  auto s = robotStateToIdl(T);
  s.source("drive");
  return s;
}

TEST(SceneNode, DepthHeightsFollowTheWallUnderTheRobotAndTheRobotIsNeverSeen) {
  testing::TempDir dir;
  SceneNode node(loadScene(stepScene(dir)), SceneNodeOptions{});
  ASSERT_EQ(node.camera().width_px, 64);
  ASSERT_NEAR(node.camera().pixel_size_m, 0.4 / 64, 1e-15);
  ASSERT_DOUBLE_EQ(node.camera().near_m, 0.05);
  ASSERT_DOUBLE_EQ(node.camera().far_m, -0.05);
  // The sealing plane 20 mm above the lower wall; yawed so that the step crosses the image
  // at an angle: rows and columns are both checked.
  for (const double yaw : {0.0, 0.7, -2.0}) {
    const double z_R = 0.02;
    node.applyRobotStates({stateAt(0.25, -0.1, z_R, yaw)});
    const DepthImage image = node.renderDepth();
    ASSERT_EQ(image.height_m.size(), 64u * 64u);
    const Pose T_W_R = node.robotPoseInWall();
    int checked = 0, higher = 0;
    for (int row = 0; row < image.height_px; ++row) {
      for (int col = 0; col < image.width_px; ++col) {
        const Eigen::Vector3d p_W =
            T_W_R * Eigen::Vector3d(node.camera().pixelCentreX_m(col), node.camera().pixelCentreY_m(row), 0.0);
        if (std::abs(p_W.x() - kStepX_m) < image.pixel_size_m) continue;  // the edge's pixel
        const double expected = wallHeight(p_W.x()) - z_R;
        // The robot body (3 cm above the plane, inside near) must not hide the wall.
        ASSERT_NEAR(image.at(row, col), expected, 1e-4) << "yaw " << yaw << " pixel " << row << "," << col;
        ++checked;
        higher += expected > -z_R / 2;
      }
    }
    EXPECT_GT(checked, 64 * 64 * 9 / 10);
    EXPECT_GT(higher, 100) << "the step is in view";
    EXPECT_GT(checked - higher, 100) << "the lower wall is in view";
  }
}

TEST(SceneNode, ARobotStateWithNanIsDroppedAndTheLastValidPoseHeld) {
  testing::TempDir dir;
  SceneNode node(loadScene(stepScene(dir)), SceneNodeOptions{});
  node.applyRobotStates({stateAt(0.1, 0.2, 0.0, 0.5)});
  const Pose held = node.robotPoseInWall();
  auto bad = stateAt(5, 5, 0, 0);
  bad.position_m()[1] = std::numeric_limits<double>::quiet_NaN();
  auto unnormalised = stateAt(5, 5, 0, 0);
  unnormalised.orientation_wxyz()[0] = 2.0;
  node.applyRobotStates({bad, unnormalised});
  EXPECT_EQ(node.droppedRobotStates(), 2u);
  EXPECT_LT((node.robotPoseInWall().matrix() - held.matrix()).norm(), 1e-15);
  // A valid sample after bad ones applies.
  node.applyRobotStates({bad, stateAt(0.3, 0.2, 0.0, 0.0)});
  EXPECT_EQ(node.droppedRobotStates(), 3u);
  EXPECT_NEAR(node.robotPoseInWall().translation().x(), 0.3, 1e-15);
}

TEST(SceneNode, TheScannerPoseInTheWallFrameFollowsTheRobot) {
  testing::TempDir dir;
  SceneNode node(loadScene(stepScene(dir)), SceneNodeOptions{});
  node.applyRobotStates({stateAt(1.0, 1.9, 0.01, -M_PI / 2)});
  const Eigen::Matrix4d expected = testing::homogeneous(testing::rotZ(-M_PI / 2), {1.0, 1.9, 0.01}) *
                                   testing::homogeneous(Eigen::Matrix3d::Identity(), {0, 0, 0.35}) *
                                   testing::homogeneous(testing::rotY(testing::deg(20)), {0, 0, 0});
  EXPECT_LT((node.scannerPoseInWall().matrix() - expected).norm(), 1e-12);
  // Pitched 20 degrees down towards +x_S, the beam at angle a in the scan plane points along
  // (cos 20 cos a, sin a, -sin 20 cos a) and meets the upper level of the step (12 mm up,
  // x_W = 1 > 0.3) after (0.36 m - 12 mm) / (sin 20 cos a).
  const LaserScan scan = node.scanLaser();
  const auto idl = laserScanToIdl(scan, node.scannerPoseInWall());
  ASSERT_EQ(idl.ranges_m().size(), 682u);
  for (const int beam : {300, 340, 341, 380}) {
    const double a = scan.angle_min_rad + beam * scan.angle_increment_rad;
    EXPECT_NEAR(idl.ranges_m()[beam], (0.36 - kStepHeight_m) / (std::sin(testing::deg(20)) * std::cos(a)), 1e-4)
        << "beam " << beam;
  }
  // Beams pointing away from the wall's plane (|a| > 90 deg) meet nothing.
  EXPECT_TRUE(std::isinf(idl.ranges_m()[0]));
  EXPECT_NEAR(idl.position_m()[2], 0.36, 1e-12);
}

TEST(SceneModel, StepKeepsTheRobotPoseInTheCallersState) {
  // The model contract: the pose in force is the state's; a copied state renders as the
  // original; one model steps two states (two robots) without either seeing the other.
  testing::TempDir dir;
  SceneParams params;
  const SceneModel model(loadScene(stepScene(dir)), params);
  SceneState left = model.initialState(), right = model.initialState();
  const Pose on_left = robotPoseFromIdl(stateAt(0.25, 0.0, 0.0, 0.0));  // sees the step's edge 5 cm to its right
  const Pose on_step = robotPoseFromIdl(stateAt(0.6, 0.0, kStepHeight_m, 0.0));
  model.step(left, {on_left, false, false}, 0, 5'000'000);
  model.step(right, {on_step, false, false}, 0, 5'000'000);
  const SceneState copy = left;
  SceneState copy_state = copy;
  const auto a = model.step(left, {std::nullopt, true, true}, 5'000'000, 5'000'000);
  const auto b = model.step(right, {std::nullopt, true, false}, 5'000'000, 5'000'000);
  const auto c = model.step(copy_state, {std::nullopt, true, true}, 5'000'000, 5'000'000);
  ASSERT_TRUE(a.depth && b.depth && c.depth && a.laser && c.laser);
  EXPECT_FALSE(b.laser.has_value()) << "only what is asked for";
  EXPECT_TRUE(left.T_W_R.isApprox(on_left, 0.0)) << "held without a new pose";
  EXPECT_TRUE(a.depth->height_m == c.depth->height_m);
  EXPECT_TRUE(a.laser->ranges_m == c.laser->ranges_m);
  EXPECT_TRUE(a.T_W_S.isApprox(c.T_W_S, 0.0));
  // Under the robot's centre the wall is at its sealing plane, left of the step and on it;
  // the left robot's camera (0.4 m wide) also sees the step 12 mm higher, the other one not.
  const auto centre = [](const DepthImage& d) { return d.height_m[d.height_px / 2 * d.width_px + d.width_px / 2]; };
  EXPECT_NEAR(centre(*a.depth), 0.0, 1e-6);
  EXPECT_NEAR(centre(*b.depth), 0.0, 1e-6) << "the robot on the step stands on it: its sealing plane is the step";
  EXPECT_NEAR(*std::max_element(a.depth->height_m.begin(), a.depth->height_m.end()), kStepHeight_m, 1e-5);
  EXPECT_NEAR(*std::max_element(b.depth->height_m.begin(), b.depth->height_m.end()), 0.0, 1e-5);
}

TEST(SceneModel, TwoStatesSteppedInterleavedOrOnTwoThreadsGiveWhatEachGivesAlone) {
  // The model contract: no hidden state between calls. Two robots' poses stepped on one model,
  // in turn and on two threads at once, render what each renders on a model of its own.
  testing::TempDir dir;
  const Scene scene = loadScene(stepScene(dir));
  const auto poses = [](double x0) {
    std::vector<Pose> out;
    for (int k = 0; k < 4; ++k) {
      const double x = x0 + 0.1 * k;
      out.push_back(robotPoseFromIdl(stateAt(x, 0.01 * k, x > 0.5 ? kStepHeight_m : 0.0, 0.2 * k)));
    }
    return out;
  };
  const std::vector<std::vector<Pose>> runs = {poses(0.1), poses(0.45)};
  using Frames = std::vector<SceneOutputs>;
  const auto stepAll = [](const SceneModel& model, SceneState& state, const Pose& pose, std::int64_t k) {
    return model.step(state, {pose, true, true}, k * 5'000'000, 5'000'000);
  };
  std::vector<Frames> alone(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const SceneModel own(Scene(scene), SceneParams{});
    SceneState state = own.initialState();
    for (std::size_t k = 0; k < runs[r].size(); ++k) alone[r].push_back(stepAll(own, state, runs[r][k], k));
  }
  const SceneModel shared(Scene(scene), SceneParams{});
  std::vector<SceneState> states = {shared.initialState(), shared.initialState()};
  std::vector<Frames> interleaved(runs.size());
  for (std::size_t k = 0; k < runs[0].size(); ++k) {
    for (std::size_t r = 0; r < runs.size(); ++r) interleaved[r].push_back(stepAll(shared, states[r], runs[r][k], k));
  }
  std::vector<Frames> threaded(runs.size());
  {
    std::vector<SceneState> fresh = {shared.initialState(), shared.initialState()};
    std::vector<std::thread> threads;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      threads.emplace_back([&, r] {
        for (std::size_t k = 0; k < runs[r].size(); ++k) threaded[r].push_back(stepAll(shared, fresh[r], runs[r][k], k));
      });
    }
    for (auto& t : threads) t.join();
  }
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (std::size_t k = 0; k < runs[r].size(); ++k) {
      for (const Frames* other : {&interleaved[r], &threaded[r]}) {
        ASSERT_TRUE(alone[r][k].depth && (*other)[k].depth && alone[r][k].laser && (*other)[k].laser);
        EXPECT_TRUE(alone[r][k].depth->height_m == (*other)[k].depth->height_m) << "robot " << r << " frame " << k;
        EXPECT_TRUE(alone[r][k].laser->ranges_m == (*other)[k].laser->ranges_m) << "robot " << r << " frame " << k;
        EXPECT_TRUE(alone[r][k].T_W_S.isApprox((*other)[k].T_W_S, 0.0)) << "robot " << r << " frame " << k;
      }
    }
  }
  // The two robots see different walls (the test could fail): one stands on the step at the end.
  EXPECT_FALSE(alone[0][0].depth->height_m == alone[1][0].depth->height_m);
}

TEST(SceneNodeOptions, OptionsOverrideTheSceneCameraAndBadValuesNameTheOption) {
  testing::TempDir dir;
  const Scene scene = loadScene(stepScene(dir));
  SceneNodeOptions options;
  options.depth_size_px = 128;
  options.near_m = 0.02;
  const auto params = depthCameraParams(scene, options);
  EXPECT_EQ(params.width_px, 128);
  EXPECT_EQ(params.height_px, 128);
  EXPECT_NEAR(params.pixel_size_m, 0.4 / 128, 1e-15);
  EXPECT_DOUBLE_EQ(params.near_m, 0.02);
  EXPECT_DOUBLE_EQ(params.far_m, -0.05);
  options.depth_size_px = 4096;
  try {
    depthCameraParams(scene, options);
    FAIL() << "4096 px accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--depth-size-px = 4096"), std::string::npos) << e.what();
  }
  SceneNodeOptions no_element;
  no_element.pose_element = "drone_pose";
  EXPECT_THROW(SceneNode(loadScene(stepScene(dir)), no_element), ConfigError);
}

TEST(SceneTranslate, RobotStateRoundTripsAndBadOnesAreNamed) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.5, -1.5, 0.02);
  const auto sample = robotStateToIdl(T);
  EXPECT_EQ(checkRobotState(sample), "");
  EXPECT_LT((robotPoseFromIdl(sample).matrix() - T.matrix()).norm(), 1e-12);
  auto bad = sample;
  bad.orientation_wxyz()[2] = std::numeric_limits<double>::infinity();
  EXPECT_NE(checkRobotState(bad).find("orientation_wxyz[2] = inf"), std::string::npos) << checkRobotState(bad);
  bad = sample;
  bad.position_m()[0] = std::nan("");
  EXPECT_NE(checkRobotState(bad).find("position_m[0] = nan"), std::string::npos) << checkRobotState(bad);
}

TEST(SceneTranslate, DepthImageRoundTripsWithItsSupportsAndOversizedImagesAreRefused) {
  DepthImage image;
  image.width_px = 3;
  image.height_px = 2;
  image.pixel_size_m = 0.01;
  image.near_m = 0.05;
  image.far_m = -0.05;
  image.height_m = {0.01f, -0.02f, 0.0f, 0.05f, -0.05f, 0.001f};
  image.support_px = {1, 4};
  image.support_m = {-0.011f, -0.04f};
  const auto sample = depthImageToIdl(image);
  EXPECT_EQ(sample.width_px(), 3u);
  const DepthImage back = depthImageFromIdl(sample);
  EXPECT_EQ(back.height_m, image.height_m);
  EXPECT_EQ(back.pixel_size_m, image.pixel_size_m);
  EXPECT_EQ(back.support_px, image.support_px);
  EXPECT_EQ(back.support_m, image.support_m);
  image.support_m.pop_back();  // a support without its height
  EXPECT_THROW(depthImageToIdl(image), std::invalid_argument);
  image.support_px.clear();
  image.support_m.clear();
  image.width_px = 4096;
  image.height_m.assign(4096 * 2, 0.0f);
  EXPECT_THROW(depthImageToIdl(image), std::invalid_argument);
  image.width_px = 2048;  // the largest side the topic holds
  image.height_m.assign(2048 * 2, 0.0f);
  EXPECT_EQ(depthImageToIdl(image).height_m().size(), 2048u * 2u);
}

TEST(SceneTranslate, DepthGridOfBlockMeansFitsItsTopicAndLargerOnesAreRefused) {
  // The scene's 256 x 256 image becomes 64 x 64 block means of 4 x 4 pixels (16 KiB of floats).
  std::vector<float> heights(256 * 256);
  for (std::size_t i = 0; i < heights.size(); ++i) heights[i] = static_cast<float>((i % 256) / 4) * 1e-4f;
  const HeightGrid grid = downsampleHeights(heights, 256, 256, 0.8 / 256, blockFor(256, 64));
  const auto sample = depthGridToIdl(grid);
  EXPECT_EQ(sample.size(), 64u);
  EXPECT_DOUBLE_EQ(sample.cell_m(), 0.8 / 64);
  ASSERT_EQ(sample.height_m().size(), 64u * 64u);
  EXPECT_FLOAT_EQ(sample.height_m()[5], 5e-4f);  // column 5 holds pixel columns 20..23, all 5e-4 m
  HeightGrid big{128, 0.00625, std::vector<float>(128 * 128, 0.0f)};
  EXPECT_THROW(depthGridToIdl(big), std::invalid_argument);
  HeightGrid torn{64, 0.0125, std::vector<float>(10, 0.0f)};
  EXPECT_THROW(depthGridToIdl(torn), std::invalid_argument);
}

}  // namespace
}  // namespace climbsim::scene
