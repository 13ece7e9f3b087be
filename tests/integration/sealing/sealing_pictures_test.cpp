// The sealing pictures a scenario asks for (pictures.sealing_at_s), end to end with real
// processes: climbsim-sealing publishes them on the reliable sealing/SealingPicture and
// climbsim-recorder (a roster member) writes pictures/sealing_<kind>_<t>s.png; the pictures
// decode, a time after the run's end gives none, and trace.csv is the same bytes as without
// pictures.

#include <gtest/gtest.h>

#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

constexpr int kSteps = 40;  // 0.2 s at 5 ms

/// crack-descent with the default robot and `pictures` as its pictures line, in the run's dir.
fs::path writeScenario(const LockstepRun& run, const std::string& pictures) {
  std::ifstream in(std::string(CLIMBSIM_SCENARIOS_DIR) + "/crack-descent.yaml");
  const fs::path path = run.dir() / "scenario-in.yaml";
  std::ofstream out(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("robot:", 0) == 0) line = std::string("robot: ") + CLIMBSIM_ROBOTS_DIR + "/cromsci.yaml";
    if (line.rfind("pictures:", 0) == 0) line = "pictures: " + pictures;
    out << line << "\n";
  }
  return path;
}

/// clock + depth feeder + sealing + recorder (leakage only); returns the run directory.
fs::path runWithPictures(const std::string& tag, const std::string& pictures) {
  LockstepRun run(tag);
  const fs::path scenario = writeScenario(run, pictures);
  const fs::path out = run.dir() / "run";
  run.startClock("feeder,sealing,recorder", {"--steps", std::to_string(kSteps), "--step-ms", "5"});
  run.start("feeder", "climbsim-test-depth-feeder", {"--name", "feeder", "--seed", "5"});
  run.start("sealing", "climbsim-sealing", {"--name", "sealing", "--scenario", scenario.string()});
  run.start("recorder", "climbsim-recorder",
            {"--name", "recorder", "--scenario", scenario.string(), "--out", out.string(), "--inputs", "leakage"});
  const auto codes = run.waitAll(120s);
  for (const char* name : {"clock", "feeder", "sealing", "recorder"}) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  return out;
}

TEST(SealingPictures, TheRecorderWritesThePicturesOfTheRequestedTimesAndTheTraceIsUnchanged) {
  const fs::path with = runWithPictures("sealing-pictures", "{sealing_at_s: [0.02, 0.052, 0.1, 5]}");
  for (const char* t : {"0.02", "0.052", "0.1"}) {
    for (const char* kind : {"edges", "gaps"}) {
      const fs::path png = with / "pictures" / (std::string("sealing_") + kind + "_" + t + "s.png");
      ASSERT_TRUE(fs::exists(png)) << png;
      const cv::Mat img = cv::imread(png.string(), cv::IMREAD_COLOR);
      ASSERT_FALSE(img.empty()) << png;
      EXPECT_EQ(img.cols, 256) << png;  // the sealing's default camera
      EXPECT_EQ(img.rows, 256) << png;
    }
  }
  // 5 s is after the end of the run (0.2 s): nothing, and the recorder did not wait for it.
  EXPECT_FALSE(fs::exists(with / "pictures" / "sealing_edges_5s.png"));
  // The feeder's surfaces differ from step to step: pictures of different times differ.
  EXPECT_NE(readFile(with / "pictures" / "sealing_edges_0.02s.png"),
            readFile(with / "pictures" / "sealing_edges_0.1s.png"));

  const fs::path without = runWithPictures("sealing-no-pictures", "{}");
  EXPECT_FALSE(fs::exists(without / "pictures"));
  const std::string trace = readFile(with / "trace.csv");
  EXPECT_GT(std::count(trace.begin(), trace.end(), '\n'), kSteps - 2);
  EXPECT_TRUE(trace == readFile(without / "trace.csv")) << "pictures changed trace.csv";
}

}  // namespace
}  // namespace climbsim::testing
