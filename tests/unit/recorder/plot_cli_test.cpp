// climbsim-plot as a process on a small synthetic run directory (trace.csv with the recorder's
// columns, scenario.yaml naming the default robot): every PNG is written and decodes with the
// expected size; bad input is exit 2 with one line naming file, line, column and value.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "node/trace_recorder.hpp"

namespace fs = std::filesystem;

namespace {

struct Result {
  int code = -1;
  std::string output;
};

Result run(const std::string& args) {
  Result r;
  const std::string cmd = std::string(CLIMBSIM_PLOT_EXE) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) r.output += buf;
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// A run directory of 1 s at 5 ms with smooth made-up values; returns its path.
fs::path makeRunDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("climbsim_plot_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string robot_file = std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml";
  const auto geometry = climbsim::computeGeometry(climbsim::loadRobotDescription(robot_file));
  std::vector<std::string> segments;
  for (const auto& s : geometry.segments) segments.push_back(s.name);
  const auto columns = climbsim::recorder::traceColumns(segments, 3);
  std::ofstream trace(dir / "trace.csv");
  for (std::size_t c = 0; c < columns.size(); ++c) trace << (c ? "," : "") << columns[c];
  trace << "\n";
  for (int i = 0; i <= 200; ++i) {
    const double t = i * 0.005, rise = 1.0 - std::exp(-t / 0.2);
    std::vector<double> row = {t, 2200.0 * rise, 0.01 * std::sin(6 * t), -0.005 * std::cos(6 * t)};
    for (int k = 1; k <= 7; ++k) row.push_back(100000.0 - rise * (12000.0 + 600.0 * k));
    row.push_back(100000.0 - 30000.0 * rise);
    for (int k = 1; k <= 7; ++k) row.push_back(0.5 + 0.4 * std::sin(3 * t + k));
    for (std::size_t s = 0; s < segments.size(); ++s) row.push_back(1e-5);
    for (double v : {1.0, 1.2, 0.0, 0.0, 0.0, -M_PI / 2}) row.push_back(v);
    for (int k = 1; k <= 3; ++k) row.push_back(rise * (250.0 + 60.0 * k));
    for (int k = 1; k <= 3; ++k) row.push_back(0.001 * k * t);
    row.push_back(i < 2 ? 0.0 : 2200.0);  // downforce_setpoint_n: stated from row 2 on
    for (std::size_t c = 0; c < row.size(); ++c) trace << (c ? "," : "") << row[c];
    trace << "\n";
  }
  std::ifstream in(std::string(CLIMBSIM_SCENARIOS_DIR) + "/crack-descent.yaml");
  std::ofstream scenario(dir / "scenario.yaml");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("robot:", 0) == 0) line = "robot: " + robot_file;
    if (line.rfind("pictures:", 0) == 0) line = "pictures: {sealing_at_s: [0.5], ring_at_s: [0.5, 1, 5]}";
    scenario << line << "\n";
  }
  return dir;
}

TEST(ClimbsimPlot, WritesEveryPlotAsADecodablePng) {
  const fs::path dir = makeRunDir("ok");
  const Result r = run(dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  struct Expected {
    const char* file;
    int width, height;
  };
  // Charts: 1200 wide, title band 44 + panels + x label band 46 (small multiples: a panel per
  // chamber, valve, wheel); ring pictures 760 + 170 x 760.
  for (const Expected& e : {Expected{"downforce.png", 1200, 44 + 380 + 2 * 200 + 46},
                            Expected{"pressures.png", 1200, 44 + 8 * 130 + 46},
                            Expected{"valves.png", 1200, 44 + 7 * 120 + 46},
                            Expected{"wheel_loads.png", 1200, (44 + 3 * 150 + 46) + (3 * 150 + 46)},
                            Expected{"ring_0.5s.png", 930, 760}, Expected{"ring_1s.png", 930, 760}}) {
    const fs::path png = dir / "plots" / e.file;
    ASSERT_TRUE(fs::exists(png)) << png << "\n" << r.output;
    const cv::Mat img = cv::imread(png.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(img.empty()) << png;
    EXPECT_EQ(img.cols, e.width) << e.file;
    EXPECT_EQ(img.rows, e.height) << e.file;
    cv::Scalar mean, stddev;
    cv::meanStdDev(img, mean, stddev);
    EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 10.0) << e.file << " is blank";
  }
  // 5 s is past the end of the 1 s trace: skipped with a warning, not drawn.
  EXPECT_FALSE(fs::exists(dir / "plots" / "ring_5s.png"));
  EXPECT_NE(r.output.find("ring picture at 5 s skipped"), std::string::npos) << r.output;

  const Result other = run(dir.string() + " --out " + (dir / "elsewhere").string());
  ASSERT_EQ(other.code, 0) << other.output;
  EXPECT_TRUE(fs::exists(dir / "elsewhere" / "valves.png"));
  if (std::getenv("CLIMBSIM_KEEP_TEST_DIRS") == nullptr) fs::remove_all(dir);
}

TEST(ClimbsimPlot, ANonNumericCellIsExit2WithOneLine) {
  const fs::path dir = makeRunDir("badcell");
  std::ifstream in(dir / "trace.csv");
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::string s = text.str();
  // Line 4 (the third row): its downforce cell becomes "oops".
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) pos = s.find('\n', pos) + 1;
  const std::size_t first_comma = s.find(',', pos), second_comma = s.find(',', first_comma + 1);
  s.replace(first_comma + 1, second_comma - first_comma - 1, "oops");
  std::ofstream(dir / "trace.csv") << s;
  const Result r = run(dir.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("trace.csv:4: column downforce_n = 'oops': not a number"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  fs::remove_all(dir);
}

TEST(ClimbsimPlot, AMissingColumnOrTraceIsExit2) {
  const fs::path dir = makeRunDir("nocol");
  std::ifstream in(dir / "trace.csv");
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::string s = text.str();
  s.replace(s.find("wheel2_slip_mps"), 15, "wheel2_slipXmps");
  std::ofstream(dir / "trace.csv") << s;
  Result r = run(dir.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("trace.csv:1: no column 'wheel2_slip_mps'"), std::string::npos) << r.output;

  fs::remove(dir / "trace.csv");
  r = run(dir.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("trace.csv: cannot read"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

}  // namespace
