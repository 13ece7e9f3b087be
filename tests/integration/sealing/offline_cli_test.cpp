// `climbsim-sealing --offline` end to end: the real executable on depth files written here;
// the JSON against the model run in this process, the pictures' sizes, and exit code 2 with
// a line naming the file for every bad input.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "climbsim/process.hpp"
#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"

#ifndef CLIMBSIM_BIN_DIR
#error "CLIMBSIM_BIN_DIR must point at the built executables"
#endif

namespace climbsim::sealing::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct Outcome {
  int code = -1;
  std::string output;
};

fs::path workDir(const std::string& name) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "sealing-offline" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Outcome runSealing(const fs::path& dir, std::vector<std::string> args) {
  ProcessSpec spec;
  spec.argv = {std::string(CLIMBSIM_BIN_DIR) + "/climbsim-sealing"};
  spec.argv.insert(spec.argv.end(), args.begin(), args.end());
  spec.output_file = (dir / "sealing.log").string();
  fs::remove(spec.output_file);
  ChildProcess child(spec);
  Outcome out;
  const auto code = child.waitFor(60s);
  out.code = code ? *code : -1;
  std::ifstream in(spec.output_file);
  std::stringstream text;
  text << in.rdbuf();
  out.output = text.str();
  return out;
}

void writeTiff(const fs::path& path, const DepthGrid& depth) {
  cv::Mat image(depth.grid.height_px, depth.grid.width_px, CV_32FC1, const_cast<float*>(depth.height_m.data()));
  ASSERT_TRUE(cv::imwrite(path.string(), image));
}

DepthGrid crackedWall(const PixelGrid& g) {
  DepthGrid depth = flatWall(g);
  addCrack(depth, Crack{0.0, 0.0, 0.3, 0.012, 0.02, 0.0, 1e9});
  return depth;
}

void expectJsonMatchesModel(const fs::path& json_path, const DepthGrid& depth) {
  std::ifstream in(json_path);
  ASSERT_TRUE(in) << json_path;
  const auto json = nlohmann::json::parse(in);
  const auto m = model(depth.grid);
  const auto expected = m.compute(depth);
  const auto closed = m.closedLeaks();
  ASSERT_EQ(json["segments"].size(), m.segmentCount());
  double total = 0, basic = 0;
  int leaking = 0;
  for (std::size_t s = 0; s < m.segmentCount(); ++s) {
    const auto& seg = json["segments"][s];
    EXPECT_EQ(seg["name"], geometry().segments[s].name);
    EXPECT_EQ(seg["pixels"].get<std::size_t>(), expected.segments[s].pixels);
    // Doubles in JSON round-trip exactly.
    EXPECT_EQ(seg["leak_area_m2"].get<double>(), expected.segments[s].leak_area_m2) << seg["name"];
    EXPECT_EQ(seg["mean_gap_m"].get<double>(), expected.segments[s].mean_gap_m) << seg["name"];
    EXPECT_EQ(seg["basic_leak_area_m2"].get<double>(), closed[s].leak_area_m2);
    total += seg["leak_area_m2"].get<double>();
    basic += seg["basic_leak_area_m2"].get<double>();
    leaking += seg["leak_area_m2"].get<double>() > closed[s].leak_area_m2 ? 1 : 0;
  }
  EXPECT_EQ(json["total_leak_area_m2"].get<double>(), total);
  EXPECT_EQ(json["total_basic_leak_area_m2"].get<double>(), basic);
  EXPECT_EQ(json["width_px"], depth.grid.width_px);
  EXPECT_EQ(json["height_px"], depth.grid.height_px);
  // A crack through the centre crosses two inner and two outer arcs.
  EXPECT_EQ(leaking, 4);
}

void expectPictures(const fs::path& out, const PixelGrid& g) {
  for (const char* name : {"edges.png", "gaps.png"}) {
    const cv::Mat picture = cv::imread((out / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(picture.empty()) << name;
    EXPECT_EQ(picture.cols, g.width_px) << name;
    EXPECT_EQ(picture.rows, g.height_px) << name;
    EXPECT_EQ(picture.type(), CV_8UC3) << name;
  }
}

TEST(SealingOffline, Float32TiffGivesTheModelsLeakageAndTwoPictures) {
  const auto dir = workDir("tiff");
  const PixelGrid g = grid(256, 256);
  const DepthGrid depth = crackedWall(g);
  writeTiff(dir / "depth.tif", depth);
  const auto out = runSealing(dir, {"--offline", (dir / "depth.tif").string(), "--robot", robotFile(), "--out",
                                    (dir / "out").string()});
  ASSERT_EQ(out.code, 0) << out.output;
  expectJsonMatchesModel(dir / "out" / "leakage.json", depth);
  expectPictures(dir / "out", g);
}

TEST(SealingOffline, SixteenBitPngWithScaleAndOffsetAndNpyGiveTheSameAsTheirHeights) {
  const auto dir = workDir("png-npy");
  const PixelGrid g = PixelGrid{300, 320, 0.9 / 300};  // 0.9 m wide, not square
  DepthGrid depth = crackedWall(g);
  // 16 bit over ±0.05 m: write counts, and compare against the heights they stand for.
  const double scale = 0.1 / 65535, offset = -0.05;
  cv::Mat counts(g.height_px, g.width_px, CV_16UC1);
  for (std::size_t i = 0; i < depth.height_m.size(); ++i) {
    const auto count = static_cast<std::uint16_t>(std::lround((depth.height_m[i] - offset) / scale));
    counts.at<std::uint16_t>(static_cast<int>(i / g.width_px), static_cast<int>(i % g.width_px)) = count;
    depth.height_m[i] = static_cast<float>(offset + scale * count);
  }
  ASSERT_TRUE(cv::imwrite((dir / "depth.png").string(), counts));
  std::ostringstream scale_text, offset_text;
  scale_text.precision(17);
  scale_text << scale;
  offset_text << offset;
  auto out = runSealing(dir, {"--offline", (dir / "depth.png").string(), "--robot", robotFile(), "--out",
                              (dir / "png").string(), "--scale", scale_text.str(), "--height-offset-m", offset_text.str(),
                              "--view-m", "0.9"});
  ASSERT_EQ(out.code, 0) << out.output;
  expectJsonMatchesModel(dir / "png" / "leakage.json", depth);
  expectPictures(dir / "png", g);

  // The same heights as .npy.
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(g.height_px) + ", " +
                       std::to_string(g.width_px) + "), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  {
    std::ofstream npy(dir / "depth.npy", std::ios::binary);
    npy.write("\x93NUMPY\x01\x00", 8);
    npy.put(static_cast<char>(header.size() & 0xff));
    npy.put(static_cast<char>(header.size() >> 8));
    npy << header;
    npy.write(reinterpret_cast<const char*>(depth.height_m.data()),
              static_cast<std::streamsize>(depth.height_m.size() * sizeof(float)));
  }
  out = runSealing(dir, {"--offline", (dir / "depth.npy").string(), "--robot", robotFile(), "--out",
                         (dir / "npy").string(), "--view-m", "0.9"});
  ASSERT_EQ(out.code, 0) << out.output;
  expectJsonMatchesModel(dir / "npy" / "leakage.json", depth);
}

TEST(SealingOffline, BadInputsExitWithCode2AndALineNamingTheFile) {
  const auto dir = workDir("bad");
  const PixelGrid g = grid(128, 128);
  DepthGrid nan = flatWall(g);
  nan.height_m[3 * 128 + 4] = std::numeric_limits<float>::quiet_NaN();
  writeTiff(dir / "nan.tif", nan);
  writeTiff(dir / "small.tif", flatWall(grid(64, 64)));
  ASSERT_TRUE(cv::imwrite((dir / "eight.png").string(), cv::Mat(64, 64, CV_8UC1, cv::Scalar(1))));
  ASSERT_TRUE(cv::imwrite((dir / "sixteen.png").string(), cv::Mat(64, 64, CV_16UC1, cv::Scalar(1))));
  { std::ofstream(dir / "robot.yaml") << "name: broken\nbody: {diameter_m: -1}\n"; }
  const std::string robot = robotFile();
  const std::string out = (dir / "out").string();
  struct Case {
    std::vector<std::string> args;
    std::string names;    // the file the error line must name
    std::string problem;  // and a word of the problem
  };
  const std::vector<Case> cases = {
      {{"--offline", (dir / "missing.tif").string(), "--robot", robot, "--out", out}, "missing.tif", "no such file"},
      {{"--offline", (dir / "nan.tif").string(), "--robot", robot, "--out", out}, "nan.tif", "(row 3, col 4)"},
      {{"--offline", (dir / "eight.png").string(), "--robot", robot, "--out", out, "--scale", "1e-6"}, "eight.png",
       "8UC1"},
      {{"--offline", (dir / "sixteen.png").string(), "--robot", robot, "--out", out}, "sixteen.png", "--scale"},
      {{"--offline", (dir / "small.tif").string(), "--robot", robot, "--out", out, "--view-m", "0.4"}, "small.tif",
       "does not fit"},
      {{"--offline", (dir / "nan.tif").string(), "--robot", (dir / "robot.yaml").string(), "--out", out},
       "robot.yaml", "diameter"},
      {{"--offline", (dir / "small.tif").string(), "--robot", robot}, "--out", "--out"},
  };
  for (const auto& c : cases) {
    const auto result = runSealing(dir, c.args);
    EXPECT_EQ(result.code, 2) << c.names << "\n" << result.output;
    std::istringstream lines(result.output);
    std::string line;
    bool named = false;
    while (std::getline(lines, line)) {
      named = named || (line.find(c.names) != std::string::npos && line.find(c.problem) != std::string::npos);
    }
    EXPECT_TRUE(named) << "no line names " << c.names << " and " << c.problem << ":\n" << result.output;
  }
}

}  // namespace
}  // namespace climbsim::sealing::testing
