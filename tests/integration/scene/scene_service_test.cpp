// climbsim-scene with the real clock and a pose feeder on real Fast DDS: depth heights against
// a wall with a known step, the robot body never in the image, NaN poses dropped, frames of
// 256x256 and 1024x1024 through the QoS profile, bad scene files exit 2.

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>

#include "lockstep_harness.hpp"
#include "scene_feeder_pose.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kStepX_m = 0.3;         ///< the step's edge along x_W
constexpr double kStepHeight_m = 0.012;  ///< the upper level's height above the lower one
constexpr double kBodyHeight_m = 0.03;   ///< the robot body's plate, above the sealing plane
constexpr double kImageWidth_m = 0.4;

/// The scene of the tests: wall (z_W = 0, 12 mm higher for x_W >= 0.3 m), robot body (a 0.3 m
/// plate 30 mm above its sealing plane: inside the camera's near limit, so it would show if
/// it were not left out), initial robot offset (0.5, 0.5, 0.02).
std::string writeStepScene(const std::filesystem::path& dir, int size_px) {
  std::filesystem::create_directories(dir);
  const std::string x = std::to_string(kStepX_m), h = std::to_string(kStepHeight_m);
  std::ofstream(dir / "wall.obj") << "v -2 -2 0\nv " << x << " -2 0\nv " << x << " 2 0\nv -2 2 0\n"
                                  << "v " << x << " -2 " << h << "\nv 2 -2 " << h << "\nv 2 2 " << h << "\nv " << x
                                  << " 2 " << h << "\nv " << x << " -2 0\nv " << x << " 2 0\n"
                                  << "f 1 2 3\nf 1 3 4\nf 5 6 7\nf 5 7 8\nf 9 5 8\nf 9 8 10\n";
  std::ofstream(dir / "body.stl") << "solid body\n"
                                     "facet normal 0 0 1\n outer loop\n  vertex -0.15 -0.15 0.03\n  vertex 0.15 -0.15 0.03\n"
                                     "  vertex 0.15 0.15 0.03\n endloop\nendfacet\n"
                                     "facet normal 0 0 1\n outer loop\n  vertex -0.15 -0.15 0.03\n  vertex 0.15 0.15 0.03\n"
                                     "  vertex -0.15 0.15 0.03\n endloop\nendfacet\nendsolid body\n";
  const std::string px = std::to_string(size_px);
  std::ofstream(dir / "step.xml")
      << "<scene>\n"
         "  <part name=\"WALL\" attached_to=\"ROOT\" offset=\"0 0 6 90 0 0\"/>\n"
         "  <part name=\"CONCRETE\" file=\"wall.obj\" attached_to=\"WALL\"/>\n"
         "  <part name=\"ROBOT\" file=\"body.stl\" attached_to=\"WALL\" offset=\"0.5 0.5 0.02 0 0 0\"/>\n"
         "  <part name=\"DEPTH_CAMERA\" attached_to=\"ROBOT\"/>\n"
         "  <element name=\"robot_pose\" type=\"3d Pose\" angle_type=\"rad\" attached_to=\"ROBOT\"/>\n"
         "  <camera name=\"depth_cam\" type=\"orthographic\" near_limit=\"-0.05\" far_limit=\"0.05\" width=\""
      << px << "\" height=\"" << px << "\" size=\"0.4 0.4\" attached_to=\"DEPTH_CAMERA\"/>\n"
      << "</scene>\n";
  return (dir / "step.xml").string();
}

struct RecordedImage {
  std::uint64_t step = 0;
  int width_px = 0, height_px = 0, stride = 1;
  double pixel_size_m = 0, near_m = 0, far_m = 0;
  std::size_t values = 0;
  std::vector<double> heights;  ///< every stride-th pixel of every stride-th row
};

std::vector<RecordedImage> readRecord(const std::string& text) {
  std::vector<RecordedImage> out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream f(line);
    std::string kind, token;
    RecordedImage image;
    f >> kind >> image.step >> image.width_px >> image.height_px >> image.stride;
    f >> token;
    image.pixel_size_m = std::strtod(token.c_str(), nullptr);
    f >> token;
    image.near_m = std::strtod(token.c_str(), nullptr);
    f >> token;
    image.far_m = std::strtod(token.c_str(), nullptr);
    f >> image.values;
    while (f >> token) image.heights.push_back(std::strtod(token.c_str(), nullptr));
    out.push_back(image);
  }
  return out;
}

/// Checks every recorded pixel of `image`, rendered with the robot at T_W_R, against the
/// wall's height below the pixel centre minus the sealing plane's height; returns how many
/// pixels lay on the upper level.
int checkHeights(const RecordedImage& image, const scene::Pose& T_W_R) {
  int upper = 0;
  std::size_t k = 0;
  for (int row = 0; row < image.height_px; row += image.stride) {
    for (int col = 0; col < image.width_px; col += image.stride, ++k) {
      const double x_C = (col + 0.5 - 0.5 * image.width_px) * image.pixel_size_m;
      const double y_C = (0.5 * image.height_px - row - 0.5) * image.pixel_size_m;
      const Eigen::Vector3d p_W = T_W_R * Eigen::Vector3d(x_C, y_C, 0.0);
      const double h = k < image.heights.size() ? image.heights[k] : std::nan("");
      EXPECT_GT(std::abs(h - kBodyHeight_m), 1e-3) << "the robot body shows at step " << image.step;
      if (std::abs(p_W.x() - kStepX_m) < image.pixel_size_m) continue;
      const bool on_upper = p_W.x() >= kStepX_m;
      const double expected = (on_upper ? kStepHeight_m : 0.0) - T_W_R.translation().z();
      EXPECT_NEAR(h, expected, 1e-4) << "step " << image.step << " pixel " << row << "," << col;
      upper += on_upper;
      if (::testing::Test::HasFailure()) return upper;
    }
  }
  return upper;
}

/// clock + climbsim-scene + the feeder; returns the recorded images.
std::vector<RecordedImage> runScene(LockstepRun& run, int size_px, int steps, int stride,
                                    const std::vector<std::string>& feeder_extra) {
  const auto scene_file = writeStepScene(run.dir() / "scene", size_px);
  run.startClock("scene,feeder", {"--steps", std::to_string(steps), "--step-ms", "5"});
  run.start("scene", "climbsim-scene", {"--name", "scene", "--scene", scene_file, "--outputs", "depth"});
  std::vector<std::string> args = {"--name", "feeder", "--record", (run.dir() / "feeder.rec").string(), "--stride",
                                   std::to_string(stride)};
  args.insert(args.end(), feeder_extra.begin(), feeder_extra.end());
  run.start("feeder", "climbsim-test-scene-feeder", args);
  const auto codes = run.waitAll(180s);
  for (const std::string name : {"clock", "scene", "feeder"}) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  return readRecord(run.record("feeder"));
}

TEST(SceneService, DepthHeightsMatchTheWallUnderTheMovingRobotAndNanPosesAreHeld) {
  LockstepRun run("scene-256");
  constexpr int kSteps = 30, kNanStep = 10;
  const auto images = runScene(run, 256, kSteps, 4, {"--nan-at", std::to_string(kNanStep)});
  // The feeder reads at steps 1..kSteps-1 the images of steps 0..kSteps-2.
  ASSERT_EQ(images.size(), static_cast<std::size_t>(kSteps - 1)) << run.allLogs();
  for (const auto& image : images) {
    ASSERT_EQ(image.width_px, 256);
    ASSERT_EQ(image.values, 256u * 256u);
    ASSERT_NEAR(image.pixel_size_m, kImageWidth_m / 256, 1e-15);
    ASSERT_DOUBLE_EQ(image.near_m, 0.05);
    // Image s is rendered from the RobotState of step s - 1; before any, the XML offset holds;
    // the NaN sample of kNanStep is dropped, so image kNanStep + 1 keeps pose kNanStep - 1.
    scene::Pose T_W_R = scene::Pose::Identity();
    T_W_R.translation() = Eigen::Vector3d(0.5, 0.5, 0.02);
    if (image.step >= 1) {
      const std::uint64_t from = image.step - 1 == kNanStep ? kNanStep - 1 : image.step - 1;
      T_W_R = scene::testing::feederPose(from);
    }
    const int upper = checkHeights(image, T_W_R);
    if (::testing::Test::HasFailure()) break;
    // The robot starts on the upper level (x 0.5) and the path crosses the step.
    EXPECT_GT(upper, 0) << "step " << image.step;
  }
  EXPECT_NE(run.log("scene").find("dropped RobotState from 'feeder' step 10: position_m[0] = nan"), std::string::npos)
      << run.log("scene");
  EXPECT_NE(run.log("scene").find("dropped_samples=1 (RobotState samples)"), std::string::npos) << run.log("scene");
}

TEST(SceneService, FramesOf1024By1024PixelsPassBetweenProcesses) {
  LockstepRun run("scene-1024");
  constexpr int kSteps = 6;
  const auto images = runScene(run, 1024, kSteps, 16, {});
  ASSERT_EQ(images.size(), static_cast<std::size_t>(kSteps - 1)) << run.allLogs();
  for (const auto& image : images) {
    ASSERT_EQ(image.values, 1024u * 1024u);
    ASSERT_EQ(image.heights.size(), 64u * 64u);
    scene::Pose T_W_R = scene::Pose::Identity();
    T_W_R.translation() = Eigen::Vector3d(0.5, 0.5, 0.02);
    if (image.step >= 1) T_W_R = scene::testing::feederPose(image.step - 1);
    checkHeights(image, T_W_R);
    if (::testing::Test::HasFailure()) break;
  }
}

TEST(SceneService, ABadSceneFileExitsWithCode2AndOneLineNamingFileLineAndValue) {
  LockstepRun run("scene-bad");
  std::filesystem::create_directories(run.dir());
  const auto file = (run.dir() / "bad.xml").string();
  std::ofstream(file) << "<scene>\n  <part name=\"WALL\" attached_to=\"ROOT\"/>\n"
                         "  <part name=\"CUBE\" file=\"\" attached_to=\"BRIDGE\"/>\n</scene>\n";
  run.start("scene", "climbsim-scene", {"--name", "scene", "--scene", file});
  const auto codes = run.waitAll(30s);
  ASSERT_EQ(codes.count("scene"), 1u);
  EXPECT_EQ(codes.at("scene"), 2) << run.log("scene");
  EXPECT_NE(run.log("scene").find(file + ":3:"), std::string::npos) << run.log("scene");
  EXPECT_NE(run.log("scene").find("attached_to=\"BRIDGE\""), std::string::npos) << run.log("scene");
}

}  // namespace
}  // namespace climbsim::testing
