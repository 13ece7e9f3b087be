// Poses of the scene graph: the offset's rotation convention, nested offsets, 3d Pose
// elements in degrees and radians, sensor mounts.

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"
#include "climbsim/wall/pose_offset.hpp"
#include "climbsim/wall/scene.hpp"
#include "scene_test_files.hpp"

namespace climbsim::scene {
namespace {

using testing::deg;
using testing::homogeneous;
using testing::rotX;
using testing::rotY;
using testing::rotZ;

constexpr double kTol = 1e-12;

TEST(ScenePose, RotationIsRollThenPitchThenYawAboutFixedAxes) {
  const double roll = 0.3, pitch = -0.7, yaw = 2.1;
  const Eigen::Matrix3d r = rotationFromRollPitchYaw(roll, pitch, yaw);
  EXPECT_LT((r - rotZ(yaw) * rotY(pitch) * rotX(roll)).norm(), kTol);
  // Fixed axes: rotating a vector by roll about x, then the result by pitch about the
  // (unmoved) y axis, then by yaw about z.
  const Eigen::Vector3d v(0.2, -1.0, 0.5);
  const Eigen::Vector3d step = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                (Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) * v));
  EXPECT_LT((r * v - step).norm(), kTol);
  // Right-handed signs: yaw 90 deg takes x to y, pitch 90 deg x to -z, roll 90 deg y to z.
  EXPECT_LT((rotationFromRollPitchYaw(0, 0, deg(90)) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), kTol);
  EXPECT_LT((rotationFromRollPitchYaw(0, deg(90), 0) * Eigen::Vector3d::UnitX() + Eigen::Vector3d::UnitZ()).norm(), kTol);
  EXPECT_LT((rotationFromRollPitchYaw(deg(90), 0, 0) * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), kTol);
}

TEST(ScenePose, OffsetIsMetresAndDegrees) {
  Pose pose;
  std::string problem;
  ASSERT_TRUE(parseOffset(" 1 -2.5 +3e-1\t10 20 -30 ", pose, problem)) << problem;
  EXPECT_LT((pose.translation() - Eigen::Vector3d(1, -2.5, 0.3)).norm(), kTol);
  EXPECT_LT((pose.linear() - rotZ(deg(-30)) * rotY(deg(20)) * rotX(deg(10))).norm(), kTol);
}

TEST(ScenePose, NestedOffsetsComposeFromTheRootDown) {
  testing::TempDir dir;
  const auto file = dir.write("nested.xml", testing::sceneXml(R"(
  <part name="A" attached_to="ROOT" offset="1 2 3 10 20 30"/>
  <part name="B" attached_to="A" offset="-0.5 0.25 2 -45 5 90"/>
  <part name="C" attached_to="ROOT:A:B" offset="0.1 0.2 0.3 0 -60 170"/>
  <part name="M" file="tetra.ply" attached_to="C" offset="0 0 0.5 180 0 0"/>
)"));
  dir.write("tetra.ply", testing::asPly(testing::tetrahedron()));
  const Scene scene = loadScene(file);

  const Eigen::Matrix4d a = homogeneous(rotZ(deg(30)) * rotY(deg(20)) * rotX(deg(10)), {1, 2, 3});
  const Eigen::Matrix4d b = homogeneous(rotZ(deg(90)) * rotY(deg(5)) * rotX(deg(-45)), {-0.5, 0.25, 2});
  const Eigen::Matrix4d c = homogeneous(rotZ(deg(170)) * rotY(deg(-60)) * rotX(0), {0.1, 0.2, 0.3});
  const Eigen::Matrix4d m = homogeneous(rotX(deg(180)), {0, 0, 0.5});
  EXPECT_LT((scene.worldPose("ROOT:A:B:C").matrix() - a * b * c).norm(), kTol);
  EXPECT_LT((scene.worldPose("B").matrix() - a * b).norm(), kTol);

  // The mesh's vertices land where the hand-built chain puts them.
  const TriangleMesh& mesh = scene.staticMesh();
  const auto tetra = testing::tetrahedron();
  ASSERT_EQ(mesh.vertices_m.size(), tetra.vertices.size());
  for (std::size_t i = 0; i < tetra.vertices.size(); ++i) {
    const Eigen::Vector4d expected = a * b * c * m * tetra.vertices[i].homogeneous();
    EXPECT_LT((mesh.vertices_m[i].cast<double>() - expected.head<3>()).norm(), 1e-5) << "vertex " << i;
  }
}

/// A wall part with a robot below it, moved by a pose element in `angle_type`.
std::string robotScene(const testing::TempDir& dir, const std::string& name, const std::string& angle_type) {
  dir.write("robot.ply", testing::asPly(testing::square(0.4, 0.0)));
  dir.write("wall.ply", testing::asPly(testing::square(2.0, 0.0)));
  return dir.write(name, testing::sceneXml(R"(
  <part name="WALL" file="wall.ply" attached_to="ROOT" offset="5 0 0 90 0 90"/>
  <part name="ROBOT" attached_to="WALL" offset="0.3 0.2 0.1 0 0 45"/>
  <part name="BODY" file="robot.ply" attached_to="ROBOT" offset="0 0 0.2 0 0 0"/>
  <element name="robot_pose" type="3d Pose" angle_type=")" + angle_type + R"(" attached_to="ROBOT"/>
)"));
}

TEST(ScenePose, PoseElementAnglesFollowItsAngleType) {
  testing::TempDir dir;
  Scene in_deg = loadScene(robotScene(dir, "deg.xml", "deg"));
  Scene in_rad = loadScene(robotScene(dir, "rad.xml", "rad"));
  in_deg.setPose("robot_pose", {0.5, -0.25, 0.0, 10.0, -20.0, 120.0});
  in_rad.setPose("robot_pose", {0.5, -0.25, 0.0, deg(10.0), deg(-20.0), deg(120.0)});
  const Eigen::Matrix4d wall = homogeneous(rotZ(deg(90)) * rotX(deg(90)), {5, 0, 0});
  const Eigen::Matrix4d robot = homogeneous(rotZ(deg(120)) * rotY(deg(-20)) * rotX(deg(10)), {0.5, -0.25, 0.0});
  EXPECT_LT((in_deg.worldPose("ROBOT").matrix() - wall * robot).norm(), kTol);
  EXPECT_LT((in_rad.worldPose("ROBOT").matrix() - wall * robot).norm(), kTol);
  // The same numbers read as radians are another pose.
  in_rad.setPose("robot_pose", {0.5, -0.25, 0.0, 10.0, -20.0, 120.0});
  EXPECT_GT((in_rad.worldPose("ROBOT").matrix() - wall * robot).norm(), 0.1);
}

TEST(ScenePose, PoseElementReplacesTheOffsetAndMovesOnlyItsSubtree) {
  testing::TempDir dir;
  Scene scene = loadScene(robotScene(dir, "robot.xml", "rad"));
  // Until set, the offset holds.
  const Eigen::Matrix4d wall = homogeneous(rotZ(deg(90)) * rotX(deg(90)), {5, 0, 0});
  EXPECT_LT((scene.worldPose("ROBOT").matrix() - wall * homogeneous(rotZ(deg(45)), {0.3, 0.2, 0.1})).norm(), kTol);
  const auto static_before = scene.staticMesh().vertices_m;
  ASSERT_EQ(static_before.size(), 4u);

  scene.setPose("robot_pose", Pose::Identity());
  EXPECT_LT((scene.worldPose("ROBOT").matrix() - scene.worldPose("WALL").matrix()).norm(), kTol);
  // BODY keeps its own offset below the moved ROBOT.
  EXPECT_LT((scene.worldPose("BODY").matrix() - wall * homogeneous(Eigen::Matrix3d::Identity(), {0, 0, 0.2})).norm(),
            kTol);
  EXPECT_EQ(scene.staticMesh().vertices_m, static_before);
  EXPECT_TRUE(scene.moving(scene.partIndex("BODY")));
  EXPECT_FALSE(scene.moving(scene.partIndex("WALL")));
  const auto moving = scene.movingMesh();
  ASSERT_EQ(moving.vertices_m.size(), 4u);
  for (const auto& v : moving.vertices_m) {
    // The square's corners are 0.2 * sqrt(2) from the body's centre, in the body's plane.
    const Eigen::Vector3d local = scene.worldPose("BODY").inverse() * v.cast<double>();
    EXPECT_NEAR(local.z(), 0.0, 1e-6);
    EXPECT_NEAR(local.head<2>().norm(), 0.2 * std::sqrt(2.0), 1e-6);
  }
  EXPECT_THROW(scene.setPose("nope", Pose::Identity()), ConfigError);
  Pose bad = Pose::Identity();
  bad.translation().x() = std::nan("");
  EXPECT_THROW(scene.setPose("robot_pose", bad), std::invalid_argument);
}

TEST(ScenePose, SensorMountsAreThePartPoseTimesTheSensorOffset) {
  testing::TempDir dir;
  const auto file = dir.write("sensors.xml", testing::sceneXml(R"(
  <part name="ROBOT" attached_to="ROOT" offset="1 1 0 0 0 90"/>
  <part name="TCP" attached_to="ROBOT" offset="0 0.1 0.5 0 0 0"/>
  <element name="robot_pose" type="3d Pose" angle_type="deg" attached_to="ROBOT"/>
  <distance_sensor name="laser_scanner" max_distance="4" scan_angle_range="240"
     angular_resolution="0.352423" offset="0 0 0.35 0 20 0" attached_to="TCP"/>
  <camera name="depth_cam" type="orthographic" near_limit="-0.05" far_limit="0.05" width="256" height="128"
     size="0.8 0.4" attached_to="ROBOT"/>
)"));
  Scene scene = loadScene(file);
  scene.setPose("robot_pose", {2, 0, 0, 0, 0, 180});
  const Eigen::Matrix4d robot = homogeneous(rotZ(deg(180)), {2, 0, 0});
  const Eigen::Matrix4d tcp = homogeneous(Eigen::Matrix3d::Identity(), {0, 0.1, 0.5});
  const Eigen::Matrix4d laser = homogeneous(rotY(deg(20)), {0, 0, 0.35});
  EXPECT_LT((scene.sensorPose("laser_scanner").matrix() - robot * tcp * laser).norm(), kTol);
  EXPECT_LT((scene.sensorPose("depth_cam").matrix() - robot).norm(), kTol);
  const auto& laser_info = scene.distanceSensor("laser_scanner");
  EXPECT_DOUBLE_EQ(laser_info.max_distance_m, 4.0);
  EXPECT_NEAR(laser_info.scan_angle_range_rad, deg(240), kTol);
  EXPECT_NEAR(laser_info.angular_resolution_rad, deg(0.352423), kTol);
  const auto& cam = scene.camera("depth_cam");
  EXPECT_EQ(cam.width_px, 256);
  EXPECT_EQ(cam.height_px, 128);
  EXPECT_DOUBLE_EQ(cam.width_m, 0.8);
  EXPECT_DOUBLE_EQ(cam.height_m, 0.4);
  EXPECT_DOUBLE_EQ(cam.near_limit_m, -0.05);
  EXPECT_THROW(scene.sensorPose("nope"), ConfigError);
}

}  // namespace
}  // namespace climbsim::scene
