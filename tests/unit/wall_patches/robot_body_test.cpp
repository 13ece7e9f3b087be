// The robot body mesh (climbsim/wall_patches/robot_body.hpp) of every shipped robot, checked
// by independent computations: the top face's area is the body outline's shoelace area, every
// edge is shared by exactly two triangles in opposite directions (closed, consistently
// oriented), the enclosed volume (divergence theorem) is the prism's plus the wheels', and each
// wheel's cylinder stands at its contact point with its radius. The scene hangs the body under
// the robot's pose only where the scene has no robot mesh of its own (robot_body_part.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <utility>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/wall/robot_body_part.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "climbsim/wall_patches/robot_body.hpp"
#include "scene_test_files.hpp"

namespace climbsim::surface {
namespace {

const std::string kRobots = CLIMBSIM_ROBOTS_DIR;

/// Every shipped robot file.
std::vector<std::string> shippedRobots() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(kRobots)) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// Shoelace area of a closed polygon (last point joined to the first) [m^2].
double shoelaceArea(const std::vector<RobotGeometry::Point>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % polygon.size()];
    twice += a.x_m * b.y_m - b.x_m * a.y_m;
  }
  return 0.5 * twice;
}

Eigen::Vector3d vertex(const SurfaceMesh& mesh, std::uint32_t i) { return mesh.vertices_m[i].cast<double>(); }

TEST(RobotBody, EveryShippedRobotsMeshIsClosedWithTheOutlinesTopAndItsWheels) {
  const auto files = shippedRobots();
  ASSERT_GE(files.size(), 4u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const RobotDescription robot = loadRobotDescription(file);
    const RobotGeometry geometry = computeGeometry(robot);
    const SurfaceMesh mesh = robotBodyMesh(geometry);
    ASSERT_FALSE(mesh.triangles.empty());

    // Top face: the triangles lying in z = kBodyTopM, facing +z.
    double top_area = 0.0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = vertex(mesh, t[0]), b = vertex(mesh, t[1]), c = vertex(mesh, t[2]);
      const auto atTop = [](const Eigen::Vector3d& p) { return std::abs(p.z() - kBodyTopM) < 1e-6; };
      if (!atTop(a) || !atTop(b) || !atTop(c)) continue;
      const double up = 0.5 * (b - a).cross(c - a).z();
      EXPECT_GT(up, 0.0) << "the top face faces away from the wall";
      top_area += up;
    }
    const double outline_area = shoelaceArea(geometry.body_outline_Robot);
    EXPECT_NEAR(top_area, outline_area, 1e-6 * outline_area);

    // Closed and consistently oriented: each directed edge once, its reverse once.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    }
    for (const auto& [edge, count] : directed) {
      ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice in one direction";
      ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
          << "edge " << edge.first << "-" << edge.second << " borders one triangle only";
    }

    // Outward normals: the enclosed volume is positive and the prism's plus the wheels'
    // (each a 24-sided prism: (n/2) r^2 sin(2 pi / n) times its width).
    double volume = 0.0;
    for (const auto& t : mesh.triangles) {
      volume += vertex(mesh, t[0]).dot(vertex(mesh, t[1]).cross(vertex(mesh, t[2]))) / 6.0;
    }
    double expected = outline_area * (kBodyTopM - kBodyBottomM);
    for (const auto& wheel : geometry.wheels) {
      const double width = wheel.kind == RobotDescription::WheelKind::kSteerable ? kSteerableTyreM
                           : wheel.kind == RobotDescription::WheelKind::kFixed   ? kFixedTyreM
                                                                                 : kCasterTyreM;
      expected += 0.5 * kWheelSides * wheel.radius_m * wheel.radius_m * std::sin(2.0 * M_PI / kWheelSides) * width;
    }
    EXPECT_NEAR(volume, expected, 1e-5 * expected);

    // Wheels after the body's 2 n vertices, 2 + 2 kWheelSides each: centred over the contact
    // point at z = r, touching the wall.
    std::size_t at = 2 * geometry.body_outline_Robot.size();
    ASSERT_EQ(mesh.vertices_m.size(), at + geometry.wheels.size() * (2 + 2 * kWheelSides));
    for (const auto& wheel : geometry.wheels) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      double lowest = 1e9;
      for (int k = 0; k < 2 + 2 * kWheelSides; ++k, ++at) {
        sum += vertex(mesh, static_cast<std::uint32_t>(at));
        lowest = std::min(lowest, vertex(mesh, static_cast<std::uint32_t>(at)).z());
      }
      const Eigen::Vector3d centre = sum / (2 + 2 * kWheelSides);
      EXPECT_NEAR(centre.x(), wheel.p_RobotWheel.x_m, 1e-6);
      EXPECT_NEAR(centre.y(), wheel.p_RobotWheel.y_m, 1e-6);
      EXPECT_NEAR(centre.z(), wheel.radius_m, 1e-6);
      EXPECT_NEAR(lowest, 0.0, 1e-6) << "the tyre touches the wall";
    }
  }
}

TEST(RobotBody, EarClippingCoversAConcavePolygon) {
  // An L of area 3 (a 2 x 2 square less a 1 x 1 corner), counter-clockwise.
  const std::vector<RobotGeometry::Point> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto triangles = triangulatePolygon(l);
  ASSERT_EQ(triangles.size(), l.size() - 2);
  double area = 0.0;
  for (const auto& t : triangles) {
    const double twice = (l[t[1]].x_m - l[t[0]].x_m) * (l[t[2]].y_m - l[t[0]].y_m) -
                         (l[t[1]].y_m - l[t[0]].y_m) * (l[t[2]].x_m - l[t[0]].x_m);
    EXPECT_GT(twice, 0.0) << "every triangle counter-clockwise, none over the notch";
    area += 0.5 * twice;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);
}

TEST(RobotBody, TheSceneGetsTheBodyWhereItsRobotHasNoMesh) {
  scene::testing::TempDir dir;
  dir.write("wall.obj", scene::testing::asObj(scene::testing::square(2.0, 0.0)));
  dir.write("robot.obj", scene::testing::asObj(scene::testing::square(0.5, 0.0)));
  const auto sceneWith = [&](const std::string& robot_file) {
    return dir.write("scene.xml", scene::testing::sceneXml(R"(
  <part name="WALL" file="wall.obj" attached_to="ROOT"/>
  <part name="ROBOT" file=")" + robot_file + R"(" attached_to="WALL"/>
  <part name="TCP" file="" attached_to="ROBOT"/>
  <element name="robot_pose" type="3d Pose" angle_type="rad" attached_to="ROBOT"/>
)"));
  };
  scene::LocalMesh body;
  body.file = "robot.yaml (body)";
  const SurfaceMesh mesh = robotBodyMesh(computeGeometry(loadRobotDescription(kRobots + "/cromsci.yaml")));
  body.vertices_m = mesh.vertices_m;
  body.triangles = mesh.triangles;

  scene::SceneDescription frames_only = scene::loadSceneDescription(sceneWith(""));
  ASSERT_TRUE(scene::attachRobotBody(frames_only, "robot_pose", body));
  const scene::PartInfo& added = frames_only.parts.back();
  EXPECT_EQ(added.full_name, "ROOT:WALL:ROBOT:ROBOT_BODY");
  EXPECT_EQ(frames_only.parts[static_cast<std::size_t>(added.parent)].name, "ROBOT");
  EXPECT_EQ(frames_only.meshes[static_cast<std::size_t>(added.mesh)].triangles.size(), mesh.triangles.size());

  scene::SceneDescription own = scene::loadSceneDescription(sceneWith("robot.obj"));
  const std::size_t parts = own.parts.size();
  EXPECT_FALSE(scene::attachRobotBody(own, "robot_pose", body)) << "the scene's own robot mesh stays";
  EXPECT_EQ(own.parts.size(), parts);
  EXPECT_FALSE(scene::attachRobotBody(frames_only, "no_such_pose", body));
}

}  // namespace
}  // namespace climbsim::surface
