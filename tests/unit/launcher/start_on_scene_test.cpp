// The launcher's start-pose check: a robot whose wheels or strips hang off the scene at the
// start is named with the start key to change, its file and line (or the --set that gave it).

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "start_on_scene.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

/// A flat wall [0, 4] x [0, 3] m in its own frame, as two triangles at z = 0.
scene::WallCoverage wall4x3() {
  scene::TriangleMesh mesh;
  mesh.vertices_m = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.part_ids = {0, 0};
  return scene::WallCoverage(mesh, 0.05);
}

RobotGeometry cromsci() {
  return computeGeometry(loadRobotDescription(std::string(CLIMBSIM_ROOT) + "/deploy/robots/cromsci.yaml"));
}

TEST(StartOnScene, ARobotInTheMiddleOfTheWallStandsOnIt) {
  const auto off = offSceneAt(wall4x3(), cromsci(), 2.0, 1.5, -M_PI / 2);
  EXPECT_FALSE(off.any());
  EXPECT_FALSE(startOffSceneMessage(off, wall4x3(), 2.0, 1.5, -90, [](const std::string&) { return "f"; }, "s.xml"));
}

TEST(StartOnScene, PastTheRightEdgeTheOuterStripsAndTheWheelsThereAreNamedAndStartXIsTheKey) {
  const RobotGeometry geometry = cromsci();
  const double r2 = geometry.ring_outer_radius_m;
  // The centre 0.1 m inside the right edge: the outer strips on that side hang past it.
  const auto off = offSceneAt(wall4x3(), geometry, 4.0 - 0.1, 1.5, 0.0);
  ASSERT_TRUE(off.any());
  EXPECT_TRUE(off.beyond_x);
  EXPECT_FALSE(off.beyond_y);
  ASSERT_FALSE(off.segments.empty());
  for (const auto& [name, share] : off.segments) {
    EXPECT_GE(share, kStartOverNothingShare) << name;
    EXPECT_LE(share, 1.0) << name;
  }
  // Wheels are named exactly when their contact point lies past x = 4 m.
  for (std::size_t w = 0; w < geometry.wheels.size(); ++w) {
    const bool past = 4.0 - 0.1 + geometry.wheels[w].p_RobotWheel.x_m > 4.0;
    const bool named = std::find(off.wheels.begin(), off.wheels.end(), int(w) + 1) != off.wheels.end();
    EXPECT_EQ(named, past) << "wheel " << w + 1;
  }
  const auto message = startOffSceneMessage(
      off, wall4x3(), 3.9, 1.5, 0.0, [](const std::string& key) { return "my.yaml:" + key; }, "scene.xml");
  ASSERT_TRUE(message);
  EXPECT_EQ(message->rfind("my.yaml:start.x_m: start.x_m = 3.9: the robot would start off the scene: ", 0), 0u)
      << *message;
  EXPECT_NE(message->find("outer1"), std::string::npos) << *message;
  EXPECT_NE(message->find("(scene.xml: walls at x 0.00..4.00 m, y 0.00..3.00 m)"), std::string::npos) << *message;
  EXPECT_EQ(message->find('\n'), std::string::npos) << "one line";
  // Just inside: every strip point on the wall.
  EXPECT_FALSE(offSceneAt(wall4x3(), geometry, 4.0 - r2 - 0.02, 1.5, 0.0).any());
}

TEST(StartOnScene, BelowTheWallItIsStartY) {
  const auto off = offSceneAt(wall4x3(), cromsci(), 2.0, 0.05, 0.3);
  ASSERT_TRUE(off.any());
  EXPECT_TRUE(off.beyond_y);
  EXPECT_FALSE(off.beyond_x);
  const auto message = startOffSceneMessage(off, wall4x3(), 2.0, 0.05, 17.2, [](const std::string& k) { return k; }, "s");
  ASSERT_TRUE(message);
  EXPECT_EQ(message->rfind("start.y_m: start.y_m = 0.05: ", 0), 0u) << *message;
}

TEST(StartOnScene, FarOffTheSceneTheLineStaysShort) {
  const auto off = offSceneAt(wall4x3(), cromsci(), 40.0, 30.0, 0.0);
  EXPECT_EQ(off.wheels.size(), 3u);
  EXPECT_EQ(off.segments.size(), 18u) << "every strip";
  const auto message = startOffSceneMessage(off, wall4x3(), 40.0, 30.0, 0.0, [](const std::string& k) { return k; },
                                            std::string(300, 'x') + ".xml");
  ASSERT_TRUE(message);
  EXPECT_NE(message->find("start = {x_m: 40, y_m: 30, yaw_deg: 0}"), std::string::npos) << *message;
  EXPECT_NE(message->find("wheels 1, 2, 3 and strips outer1 (100 %), outer2 (100 %), outer3 (100 %) and 15 more"),
            std::string::npos)
      << *message;
  EXPECT_LT(message->size(), 330u) << "scene file name cut to 60 characters: " << *message;
}

TEST(StartOnScene, TheKeyIsFoundAtItsLineOrInTheSetThatGaveIt) {
  const fs::path file = fs::temp_directory_path() / ("climbsim-start-key-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << "name: x\nrobot: r.yaml\nstart:\n  x_m: 3.8\n  y_m: 1.2\n";
  EXPECT_EQ(scenarioKeyWhere(file.string(), {}, "start.x_m"), file.string() + ":4");
  EXPECT_EQ(scenarioKeyWhere(file.string(), {}, "start.y_m"), file.string() + ":5");
  EXPECT_EQ(scenarioKeyWhere(file.string(), {"duration_s=1", "start.x_m=9"}, "start.x_m"),
            file.string() + " (--set start.x_m=9)");
  EXPECT_EQ(scenarioKeyWhere(file.string(), {}, "start.yaw_deg"), file.string());
  fs::remove(file);
}

}  // namespace
}  // namespace climbsim::launcher
