// The viewer's pure model: latest value wins, frame pacing, depth reduction, client messages,
// JSON that reads back exactly, trace reading for replays.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "client_command.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/scenario.hpp"
#include "frame_pacer.hpp"
#include "climbsim/grid_record.hpp"
#include "climbsim/height_grid.hpp"
#include "live_state.hpp"
#include "replay_run.hpp"
#include "run_description.hpp"

namespace climbsim::viewer {
namespace {

TEST(ViewerLiveState, NewerSampleWinsOlderIsIgnored) {
  LiveState state;
  EXPECT_TRUE(state.offer(ForceValue{5, 25'000'000, 2000.0, 0.01, -0.02}));
  EXPECT_FALSE(state.offer(ForceValue{4, 20'000'000, 1000.0, 0.0, 0.0}));
  EXPECT_EQ(state.force->step, 5u);
  EXPECT_EQ(state.force->downforce_n, 2000.0);
  EXPECT_TRUE(state.offer(ForceValue{6, 30'000'000, 2100.0, 0.0, 0.0}));
  EXPECT_EQ(state.force->downforce_n, 2100.0);
}

TEST(ViewerLiveState, LeakageShardsOfOneStepMerge) {
  LiveState state;
  state.offer(LeakValue{8, 0, {{"outer1", {1e-5, 1e-4}}}});
  state.offer(LeakValue{8, 0, {{"outer2", {2e-5, 2e-4}}}});
  EXPECT_EQ(state.leak->segments.size(), 2u);
  state.offer(LeakValue{12, 0, {{"outer3", {3e-5, 3e-4}}}});
  ASSERT_EQ(state.leak->segments.size(), 1u);
  EXPECT_EQ(state.leak->segments.begin()->first, "outer3");
}

TEST(ViewerLiveState, FrameJsonReadsBackExactly) {
  LiveState state;
  const double f = 2187.1234567890123;
  state.offer(ForceValue{41, 205'000'000, f, 0.1 + 0.2, -1e-17});
  state.run.phase = RunPhase::kPaused;
  state.run.roster = {{"thermo", "", 1, 0}};
  state.run.hosts["thermo"] = "lab2";
  const auto back = nlohmann::json::parse(frameJson(state).dump());
  EXPECT_EQ(back["force"]["downforce_n"].get<double>(), f);
  EXPECT_EQ(back["force"]["pf_x_m"].get<double>(), 0.1 + 0.2);
  EXPECT_EQ(back["force"]["step"].get<std::uint64_t>(), 41u);
  EXPECT_EQ(back["run"]["phase"], "paused");
  EXPECT_EQ(back["run"]["roster"][0]["host"], "lab2");
  EXPECT_FALSE(back.contains("pose"));
}

TEST(ViewerLiveState, TheSetPointIsTheOnePublishedWithTheForceAndNullWithoutOne) {
  LiveState state;
  state.offer(ForceValue{3, 15'000'000, 2100.0, 0.0, 0.0, 2000.0});  // e.g. the C client's 2000 N
  EXPECT_EQ(sampleJson(state)["force"]["setpoint_n"].get<double>(), 2000.0);
  state.offer(ForceValue{4, 20'000'000, 2100.0, 0.0, 0.0, 0.0});  // controller none: nothing published
  EXPECT_TRUE(sampleJson(state)["force"]["setpoint_n"].is_null());
}

TEST(ViewerSampleHistory, EveryNewStateOnceInOrderAndBoundedWithoutATaker) {
  LiveState state;
  SampleHistory history(4);
  history.add(state);  // nothing stamped yet: no sample
  EXPECT_EQ(history.size(), 0u);
  for (std::uint64_t step = 1; step <= 3; ++step) {
    state.offer(ForceValue{step, static_cast<std::int64_t>(step) * 5'000'000, 1000.0 + static_cast<double>(step), 0, 0});
    history.add(state);
    history.add(state);  // the same state again (a poll with nothing new): not a new sample
  }
  auto taken = history.take();
  ASSERT_EQ(taken.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(taken[i]["force"]["step"].get<std::uint64_t>(), i + 1);
  EXPECT_FALSE(taken[0].contains("run"));  // a sample holds the stamped streams only
  EXPECT_EQ(history.take().size(), 0u);    // taking empties it
  // Nobody takes: the oldest go, at most `capacity` are kept, the newest last.
  for (std::uint64_t step = 10; step < 20; ++step) {
    state.offer(ForceValue{step, 0, 0, 0, 0});
    history.add(state);
  }
  taken = history.take();
  ASSERT_EQ(taken.size(), 4u);
  EXPECT_EQ(taken[0]["force"]["step"].get<std::uint64_t>(), 16u);
  EXPECT_EQ(taken[3]["force"]["step"].get<std::uint64_t>(), 19u);
}

TEST(ViewerLiveState, FrameHoldsItsSampleAndTheRun) {
  LiveState state;
  state.offer(ForceValue{7, 35'000'000, 1500.0, 0.0, 0.0});
  state.offer(PoseValue{7, 35'000'000, {1.0, 2.0, 0.0}, {1, 0, 0, 0}, false});
  const auto sample = sampleJson(state);
  const auto frame = frameJson(state);
  EXPECT_EQ(frame["force"], sample["force"]);
  EXPECT_EQ(frame["pose"], sample["pose"]);
  EXPECT_TRUE(frame.contains("run"));
  EXPECT_FALSE(sample.contains("run"));
}

TEST(ViewerFramePacer, AtMostOneFramePerPeriodAndNoBurstAfterAGap) {
  FramePacer pacer(30.0);
  const std::int64_t period = static_cast<std::int64_t>(1e9 / 30.0);
  EXPECT_TRUE(pacer.take(1'000'000'000));
  EXPECT_FALSE(pacer.take(1'000'000'000 + period - 1));
  EXPECT_TRUE(pacer.take(1'000'000'000 + period));
  EXPECT_TRUE(pacer.take(5'000'000'000));   // a long gap
  EXPECT_FALSE(pacer.take(5'000'000'001));  // ... buys no catch-up frames
  EXPECT_THROW(FramePacer(0.0), std::invalid_argument);
}

TEST(ViewerRateMeter, SimulatedOverWallTime) {
  RateMeter meter;
  for (int i = 0; i <= 10; ++i) meter.add(i * 100'000'000LL, i * 400'000'000LL);  // 4x
  EXPECT_NEAR(meter.rate(), 4.0, 1e-9);
}

TEST(ViewerHeightGrid, BlockMeansInImageOrder) {
  std::vector<float> image(16);
  for (int i = 0; i < 16; ++i) image[i] = static_cast<float>(i);  // 4x4, row-major
  const HeightGrid grid = downsampleHeights(image, 4, 4, 0.01, 2);
  ASSERT_EQ(grid.size, 2);
  EXPECT_DOUBLE_EQ(grid.cell_m, 0.02);
  EXPECT_FLOAT_EQ(grid.height_m[0], (0 + 1 + 4 + 5) / 4.0f);
  EXPECT_FLOAT_EQ(grid.height_m[3], (10 + 11 + 14 + 15) / 4.0f);
  EXPECT_EQ(blockFor(256, 128), 2);
  EXPECT_EQ(blockFor(100, 128), 1);
  EXPECT_THROW(downsampleHeights(image, 4, 4, 0.01, 3), std::invalid_argument);
  EXPECT_THROW(downsampleHeights(image, 8, 2, 0.01, 1), std::invalid_argument);
  const auto json = heightGridJson(grid, 4, 20'000'000);
  EXPECT_EQ(json["heights_mm"].size(), 4u);
  EXPECT_DOUBLE_EQ(json["heights_mm"][0].get<double>(), 2500.0);
}

TEST(ViewerClientMessage, ClockCommandsParse) {
  auto step = std::get<ClockRequest>(parseClientMessage(R"({"cmd":"step","steps":4})"));
  EXPECT_EQ(step.kind, ClockRequest::Kind::kStep);
  EXPECT_EQ(step.steps, 4u);
  auto rtf = std::get<ClockRequest>(parseClientMessage(R"({"cmd":"rtf","value":0.5})"));
  EXPECT_EQ(rtf.kind, ClockRequest::Kind::kRealtimeFactor);
  EXPECT_EQ(rtf.realtime_factor, 0.5);
  EXPECT_EQ(std::get<ClockRequest>(parseClientMessage(R"({"cmd":"pause"})")).kind, ClockRequest::Kind::kPause);
}

TEST(ViewerClientMessage, GarbageIsNamed) {
  for (const char* garbage : {"", "garbage", "[1,2]", R"({"cmd":42})", R"({"cmd":"explode"})",
                              R"({"cmd":"step","steps":0})", R"({"cmd":"rtf"})", R"({"cmd":"rtf","value":-1})"}) {
    EXPECT_TRUE(std::holds_alternative<std::string>(parseClientMessage(garbage))) << garbage;
  }
  EXPECT_TRUE(std::holds_alternative<std::string>(parseClientMessage(std::string(5000, ' '))));
}

class ViewerReplayRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("climbsim_viewer_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "pictures");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  std::filesystem::path dir_;
};

TEST_F(ViewerReplayRun, TraceColumnsExactAndCutOffLastRowDropped) {
  write("trace.csv", "t_s,downforce_n\n0,2187.1234567890123\n0.005,1e-300\n0.01,21");
  const auto trace = loadTraceColumns((dir_ / "trace.csv").string());
  EXPECT_EQ(trace["columns"][1], "downforce_n");
  ASSERT_EQ(trace["values"][1].size(), 3u);  // "21" parses: a complete last row is kept
  EXPECT_EQ(trace["values"][1][0].get<double>(), 2187.1234567890123);
  write("trace.csv", "t_s,downforce_n\n0,1\n0.005,2\n0.01,");
  EXPECT_EQ(loadTraceColumns((dir_ / "trace.csv").string())["values"][0].size(), 2u);
}

TEST_F(ViewerReplayRun, BadTraceNamesLineColumnAndValue) {
  write("trace.csv", "t_s,downforce_n\n0,1\n0.005,abc\n0.01,3\n");
  try {
    loadTraceColumns((dir_ / "trace.csv").string());
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("trace.csv:3: column downforce_n = abc"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadTraceColumns((dir_ / "missing.csv").string()), ConfigError);
}

TEST_F(ViewerReplayRun, SealingPicturesSortedByTime) {
  for (const char* name : {"sealing_gaps_12s.png", "sealing_edges_5s.png", "sealing_gaps_5s.png", "other.png"}) {
    write(std::string("pictures/") + name, "png");
  }
  const auto pictures = listSealingPictures(dir_.string());
  ASSERT_EQ(pictures.size(), 3u);
  EXPECT_EQ(pictures[0]["t_s"].get<double>(), 5.0);
  EXPECT_EQ(pictures[2]["file"], "pictures/sealing_gaps_12s.png");
}

TEST_F(ViewerReplayRun, DepthGridsKeptEveryIntervalAndFoundByTime) {
  {
    GridRecorder recorder(gridRecordPath(dir_.string()), 100'000'000);
    for (int step = 0; step < 10; ++step) {  // every 20 ms: kept at 0, 100, 200 ms...
      const std::int64_t t_ns = step * 20'000'000LL;
      const HeightGrid grid{1, 0.01, {static_cast<float>(step) * 1e-3f}};
      recorder.offer(t_ns, heightGridJson(grid, step, t_ns).dump());
    }
  }
  std::ofstream(gridRecordPath(dir_.string()), std::ios::app) << "{\"type\":\"depth\",\"t_";  // cut off
  const auto records = loadGridRecords(gridRecordPath(dir_.string()));
  ASSERT_EQ(records.size(), 2u);
  EXPECT_DOUBLE_EQ(records[1].first, 0.1);
  EXPECT_EQ(nlohmann::json::parse(gridAt(records, 0.15))["step"], 5);
  EXPECT_EQ(nlohmann::json::parse(gridAt(records, -1.0))["step"], 0);
  EXPECT_EQ(gridAt({}, 1.0), "");
  EXPECT_TRUE(loadGridRecords((dir_ / "none.jsonl").string()).empty());
}

TEST(ViewerRunDescription, HelloHasRobotAndSetpoint) {
  const Scenario scenario = loadScenario(std::string(CLIMBSIM_SCENARIOS_DIR) + "/crack-descent.yaml");
  const auto hello = helloJson("live", scenario);
  EXPECT_EQ(hello["mode"], "live");
  EXPECT_EQ(hello["robot"]["chambers"].size(), 7u);
  EXPECT_EQ(hello["robot"]["segments"].size(), 18u);
  EXPECT_EQ(hello["robot"]["wheels"].size(), 3u);
  EXPECT_GT(hello["scenario"]["setpoint_n"].get<double>(), 0.0);
  // The body the scene has: the outline's prism (4 n - 4 triangles for n outline points), then
  // the three wheels' cylinders.
  const auto& mesh = hello["robot"]["body_mesh"];
  const std::size_t outline = hello["robot"]["body_outline"].size();
  EXPECT_EQ(mesh["body_triangles"].get<std::size_t>(), 4 * outline - 4);
  EXPECT_GT(mesh["indices"].size(), 3 * mesh["body_triangles"].get<std::size_t>());
  EXPECT_EQ(mesh["indices"].size() % 3, 0u);
  EXPECT_EQ(mesh["positions"].size() % 3, 0u);
}

}  // namespace
}  // namespace climbsim::viewer
