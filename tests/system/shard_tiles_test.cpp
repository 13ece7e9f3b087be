// Sealing shards with their own depth renderers: each shard reads only its own
// renderer's tile (`climbsim-sealing --depth-from scene-I`: the producer's DDS partition), the
// trace is the whole image's, and a shard naming no producer stops the run before step 0.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "launcher_run.hpp"

namespace climbsim::system_test {
namespace {

double deliveries(const fs::path& stats_dir, const std::string& service) {
  const std::string text = readFile(stats_dir / (service + ".json"));
  EXPECT_FALSE(text.empty()) << "no statistics of " << service << " in " << stats_dir;
  return text.empty() ? 0.0 : nlohmann::json::parse(text).at("deliveries").get<double>();
}

/// deploy/compose.hires-shards.yaml with the shards' `--depth-from` producers replaced by `from`.
fs::path shardsCompose(const std::string& name, const std::string& from) {
  std::string compose = readFile(fs::path(CLIMBSIM_ROOT) / "deploy" / "compose.hires-shards.yaml");
  const std::string original = "\"scene-${replica}\"";
  const auto at = compose.find(original);
  EXPECT_NE(at, std::string::npos) << "compose.hires-shards.yaml no longer names scene-${replica}";
  if (at != std::string::npos) compose.replace(at, original.size(), from);
  const auto scenario_at = compose.find("scenario: scenarios/");
  if (scenario_at != std::string::npos) compose.replace(scenario_at, 10, "scenario: " + std::string(CLIMBSIM_ROOT) + "/deploy/");
  const fs::path copy = fs::path(CLIMBSIM_TEST_RUNS_DIR) / ("compose." + name + ".yaml");
  fs::create_directories(copy.parent_path());
  std::ofstream(copy) << compose;
  return copy;
}

TEST(ShardTiles, EachShardReadsOnlyItsOwnRenderersTileAndTheTraceIsTheWholeImagesOne) {
  const std::string scenario = "crack-descent-hires --set duration_s=0.5";
  const auto whole = runScenario("tiles-reference", scenario);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  // Every process counts the samples its readers take (CLIMBSIM_STATS_DIR, as bench: e2e:).
  const fs::path stats = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "tiles-shards-stats";
  fs::remove_all(stats);
  fs::create_directories(stats);
  ::setenv("CLIMBSIM_STATS_DIR", stats.c_str(), 1);
  const auto tiled = runScenario("tiles-shards", scenario + " -f " + std::string(CLIMBSIM_ROOT) +
                                                     "/deploy/compose.hires-shards.yaml");
  ::unsetenv("CLIMBSIM_STATS_DIR");
  ASSERT_EQ(tiled.exit_code, 0) << tiled.output;
  const std::size_t steps = completeRows(tiled.dir / "trace.csv");
  EXPECT_EQ(steps, 100u);
  EXPECT_TRUE(readFile(whole.dir / "trace.csv") == readFile(tiled.dir / "trace.csv"))
      << "2 renderers + 2 shards gave another trace than 1 + 1";
  // Depth and sealing at 100 Hz: a frame every 2 steps. A shard takes its own renderer's frames
  // plus the clock's grants (about one per W/2 = 8 steps); reading both tiles would add another
  // frame per frame.
  const double frames = static_cast<double>(steps) / 2.0;
  for (const std::string shard : {"sealing-0", "sealing-1"}) {
    const double taken = deliveries(stats, shard);
    std::printf("%s: %.0f deliveries in %zu steps (%.0f depth frames)\n", shard.c_str(), taken, steps, frames);
    EXPECT_GE(taken, frames) << shard << " missed frames of its renderer";
    EXPECT_LT(taken, 1.5 * frames) << shard << " received the other renderer's tiles too";
  }
}

/// `scenario` (0.5 s of crack-descent-hires: 100 steps) run with deploy/compose.yaml and with
/// deploy/`compose` gives the same trace, byte for byte.
void expectTheWholeImagesTrace(const std::string& name, const std::string& scenario, const std::string& compose) {
  const auto whole = runScenario(name + "-reference", scenario);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const auto tiled = runScenario(name, scenario + " -f " + std::string(CLIMBSIM_ROOT) + "/deploy/" + compose);
  ASSERT_EQ(tiled.exit_code, 0) << tiled.output;
  EXPECT_EQ(completeRows(tiled.dir / "trace.csv"), 100u);
  EXPECT_TRUE(readFile(whole.dir / "trace.csv") == readFile(tiled.dir / "trace.csv"))
      << compose << " gave another trace than the whole image";
}

TEST(ShardTiles, OneRendererOfTheSealingsPixelsAndOneShardGiveTheWholeImagesTrace) {
  // The masked tile (--tile 0/1) against the whole image, with pixel centres (sub-pixel
  // leakage off; the default's sub-pixel shares are the next test's).
  expectTheWholeImagesTrace("masked-one", "crack-descent-hires --set duration_s=0.5 --set depth_camera.subpixel=false",
                            "compose.hires-masked.yaml");
}

TEST(ShardTiles, WithSubpixelLeakageTwoRenderersAndTwoShardsGiveTheWholeImagesTrace) {
  // depth_camera.subpixel (the default): each renderer's tiles are the sub-pixel shares' pixels
  // of its shard, its edge pixels averaged and supported as the whole image's.
  expectTheWholeImagesTrace("tiles-subpixel-shards", "crack-descent-hires --set duration_s=0.5",
                            "compose.hires-shards.yaml");
}

TEST(ShardTiles, AShardReadingFromNoInstanceIsRefusedBeforeAnythingStarts) {
  const fs::path compose = shardsCompose("tiles-bad-from", "\"scene-7${replica}\"");
  const auto run = runScenario("tiles-bad-from", "crack-descent-hires --set duration_s=0.5 -f " + compose.string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("services.sealing (sealing-0): --depth-from scene-70: no service instance of this compose "
                            "file has that name (depth renderers: scene-0, scene-1)"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(run.dir / "trace.csv")) << "a run started";
}

TEST(ShardTiles, AShardReadingFromAnInstanceThatWritesNoDepthStopsTheRunBeforeStepZeroNamingIt) {
  // thermo is on the roster but writes no depth image: the launcher cannot know what another
  // program writes, the clock's roster check at run start names it.
  const fs::path compose = shardsCompose("tiles-thermo-from", "thermo");
  const auto run = runScenario("tiles-thermo-from", "crack-descent-hires --set duration_s=0.5 -f " + compose.string());
  // Bad input, found by the shard before step 0: exit code 2 (the clock only saw a participant
  // fail and exits 1), and summary.json agrees.
  EXPECT_EQ(run.exit_code, 2) << run.output;
  const std::string summary = readFile(run.dir / "summary.json");
  EXPECT_NE(summary.find("\"outcome\": \"failed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"exit_code\": 2,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"configuration_error\": true"), std::string::npos) << summary;
  EXPECT_NE(run.output.find("ended with exit code 2 (bad configuration): participant 'sealing-"), std::string::npos)
      << run.output;
  EXPECT_NE(summary.find("\"steps\": 0,"), std::string::npos) << summary;
  // Either shard may be the first to say it.
  const bool named = summary.find("'sealing-0' reads topic 'scene/DepthImage' from 'thermo', which is not a producer "
                                  "of it on the roster (producers: scene-0, scene-1)") != std::string::npos ||
                     summary.find("'sealing-1' reads topic 'scene/DepthImage' from 'thermo', which is not a producer "
                                  "of it on the roster (producers: scene-0, scene-1)") != std::string::npos;
  EXPECT_TRUE(named) << summary;
  EXPECT_EQ(completeRows(run.dir / "trace.csv"), 0u) << "steps ran before the bad input was found";
}

TEST(ShardTiles, ATileLayoutThatMissesAShardIsRefusedBeforeAnythingStarts) {
  std::string text = readFile(shardsCompose("tiles-bad-layout", "\"scene-${replica}\""));
  const std::string tile = "--tile, \"${replica}/${replicas}\"";
  ASSERT_NE(text.find(tile), std::string::npos);
  text.replace(text.find(tile), tile.size(), "--tile, \"0/2\"");
  const fs::path compose = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "compose.tiles-bad-layout.yaml";
  std::ofstream(compose) << text;
  const auto run = runScenario("tiles-bad-layout", "crack-descent-hires --set duration_s=0.5 -f " + compose.string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("services.sealing (sealing-1): shard 1/2 reads scene-1 --tile 0/2: none renders tile 1/2"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(run.dir / "trace.csv")) << "a run started";
}

}  // namespace
}  // namespace climbsim::system_test
