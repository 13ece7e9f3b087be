// The sealing node without a network: shard assignment, shards merged by segment equal the
// unsharded leakage bit for bit, bad depth images dropped and counted with the last valid
// leakage held, translators.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <thread>
#include <utility>
#include <vector>

#include "climbsim/errors.hpp"
#include "sealing_node.hpp"
#include "climbsim/shard_tiles/shard_partition.hpp"
#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"
#include "sealing_translate.hpp"

namespace climbsim::sealing::testing {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

climbsim::DepthImage image(const DepthGrid& depth, std::uint64_t step) {
  auto sample = depthImageToIdl(depth, -0.05, 0.05);
  sample.source("scene");
  sample.step(step);
  return sample;
}

TEST(ShardSpec, ParsesIOverNAndGivesEachShardItsPartOfTheSegments) {
  const auto spec = ShardSpec::parse("1/3");
  EXPECT_EQ(spec.index, 1u);
  EXPECT_EQ(spec.count, 3u);
  const auto m = model(grid(160, 160));
  EXPECT_EQ(spec.segments(m.masks()), partitionSegments(m.masks(), 3).at(1));
  for (const char* bad : {"", "1", "1/", "/2", "2/2", "0/0", "a/2", "-1/2", "1/2/3", "1.0/2"}) {
    EXPECT_THROW(ShardSpec::parse(bad), ConfigError) << bad;
  }
  try {
    ShardSpec::parse("19/20").segments(m.masks());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--shard = '19/20'"), std::string::npos) << e.what();
  }
}

TEST(SealingNode, ShardsMergedBySegmentEqualTheUnshardedLeakageBitForBit) {
  const PixelGrid g = grid(160, 160);
  const auto m = model(g);
  for (const std::size_t n : {2u, 3u, 5u, 18u}) {
    SealingNode whole(m, ShardSpec{0, 1});
    std::vector<SealingNode> shards;
    for (std::size_t i = 0; i < n; ++i) shards.emplace_back(m, ShardSpec{i, n});
    for (std::uint64_t seed = 100; seed < 104; ++seed) {
      const auto samples = std::vector<climbsim::DepthImage>{image(randomSurface(g, seed), seed)};
      const auto all = whole.step(samples);
      std::map<std::string, std::pair<double, double>> merged;
      for (auto& shard : shards) {
        const auto part = shard.step(samples);
        for (const auto& s : part.segments()) {
          ASSERT_TRUE(merged.emplace(s.segment().c_str(), std::make_pair(s.leak_area_m2(), s.mean_gap_m())).second)
              << s.segment() << " published by two shards";
        }
      }
      ASSERT_EQ(merged.size(), all.segments().size());
      for (const auto& s : all.segments()) {
        const auto& [area, gap] = merged.at(s.segment().c_str());
        EXPECT_TRUE(sameBits(area, s.leak_area_m2())) << s.segment() << " with " << n << " shards";
        EXPECT_TRUE(sameBits(gap, s.mean_gap_m())) << s.segment() << " with " << n << " shards";
      }
    }
  }
}

TEST(SealingModel, StepKeepsEverythingThatEvolvesInTheCallersState) {
  // The model contract: a copied state steps bit for bit like the original, one model steps
  // two states (a whole sealing and a shard's) without either seeing the other, and a step
  // without an image holds the leakage in force.
  const PixelGrid g = grid(128, 128);
  const auto m = model(g);
  const auto shard = partitionSegments(m.masks(), 2).at(1);
  std::vector<std::size_t> all(m.segmentCount());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
  SealingState whole = m.initialState(all);
  SealingState part = m.initialState(shard);
  for (std::size_t s = 0; s < all.size(); ++s) EXPECT_EQ(whole.leaks[s].leak_area_m2, m.closedLeaks()[s].leak_area_m2);
  const DepthGrid first = randomSurface(g, 5), second = randomSurface(g, 6);
  m.step(whole, {&first, -0.05}, 0, 10'000'000);
  m.step(part, {&first, -0.05}, 0, 10'000'000);
  SealingState copy = whole;
  const SealingOutputs a = m.step(whole, {&second, -0.05}, 10'000'000, 10'000'000);
  const SealingOutputs b = m.step(copy, {&second, -0.05}, 10'000'000, 10'000'000);
  const SealingOutputs c = m.step(part, {&second, -0.05}, 10'000'000, 10'000'000);
  EXPECT_TRUE(a.computed && b.computed && c.computed);
  EXPECT_EQ(whole.computed, 2u);
  const SealingResult direct = m.compute(second);
  for (std::size_t s = 0; s < all.size(); ++s) {
    EXPECT_TRUE(sameBits(a.leaks[s].leak_area_m2, b.leaks[s].leak_area_m2)) << s;
    EXPECT_TRUE(sameBits(a.leaks[s].leak_area_m2, direct.segments[s].leak_area_m2)) << s;
  }
  for (const std::size_t s : shard) EXPECT_TRUE(sameBits(c.leaks[s].leak_area_m2, a.leaks[s].leak_area_m2)) << s;
  const SealingOutputs held = m.step(whole, {}, 20'000'000, 10'000'000);
  EXPECT_FALSE(held.computed);
  EXPECT_EQ(whole.computed, 2u);
  for (std::size_t s = 0; s < all.size(); ++s) EXPECT_TRUE(sameBits(held.leaks[s].leak_area_m2, a.leaks[s].leak_area_m2));
}

TEST(SealingModel, TwoStatesSteppedInterleavedOrOnTwoThreadsGiveWhatEachGivesAlone) {
  // The model contract: no hidden state between calls. Two states of the same shard (the same
  // cached region) and a whole sealing, stepped on one model in turn and on threads at once,
  // give bit for bit what each gives on a model of its own.
  const PixelGrid g = grid(128, 128);
  const auto shard = partitionSegments(model(g).masks(), 3).at(1);
  std::vector<std::size_t> all(model(g).segmentCount());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
  const std::vector<std::vector<std::size_t>> segments = {shard, shard, all};
  std::vector<std::vector<DepthGrid>> images(segments.size());
  for (std::size_t r = 0; r < segments.size(); ++r) {
    for (std::uint64_t k = 0; k < 4; ++k) images[r].push_back(randomSurface(g, 40 + 10 * r + k));
  }
  using Leaks = std::vector<std::vector<SegmentLeak>>;
  const auto run = [&](const SealingModel& m, SealingState& state, std::size_t r, std::size_t k) {
    return m.step(state, {&images[r][k], -0.05}, static_cast<std::int64_t>(k) * 10'000'000, 10'000'000).leaks;
  };
  std::vector<Leaks> alone(segments.size());
  for (std::size_t r = 0; r < segments.size(); ++r) {
    const auto own = model(g);
    SealingState state = own.initialState(segments[r]);
    for (std::size_t k = 0; k < images[r].size(); ++k) alone[r].push_back(run(own, state, r, k));
  }
  const auto shared = model(g);
  std::vector<Leaks> interleaved(segments.size());
  {
    std::vector<SealingState> states;
    for (const auto& s : segments) states.push_back(shared.initialState(s));
    for (std::size_t k = 0; k < 4; ++k) {
      for (std::size_t r = 0; r < segments.size(); ++r) interleaved[r].push_back(run(shared, states[r], r, k));
    }
  }
  std::vector<Leaks> threaded(segments.size());
  {
    std::vector<SealingState> states;
    for (const auto& s : segments) states.push_back(shared.initialState(s));
    std::vector<std::thread> threads;
    for (std::size_t r = 0; r < segments.size(); ++r) {
      threads.emplace_back([&, r] {
        for (std::size_t k = 0; k < 4; ++k) threaded[r].push_back(run(shared, states[r], r, k));
      });
    }
    for (auto& t : threads) t.join();
  }
  for (std::size_t r = 0; r < segments.size(); ++r) {
    for (std::size_t k = 0; k < 4; ++k) {
      for (const std::size_t s : segments[r]) {
        EXPECT_TRUE(sameBits(alone[r][k][s].leak_area_m2, interleaved[r][k][s].leak_area_m2)) << r << " " << k << " " << s;
        EXPECT_TRUE(sameBits(alone[r][k][s].leak_area_m2, threaded[r][k][s].leak_area_m2)) << r << " " << k << " " << s;
        EXPECT_TRUE(sameBits(alone[r][k][s].mean_gap_m, interleaved[r][k][s].mean_gap_m)) << r << " " << k << " " << s;
        EXPECT_TRUE(sameBits(alone[r][k][s].mean_gap_m, threaded[r][k][s].mean_gap_m)) << r << " " << k << " " << s;
      }
    }
  }
  // The two shard states saw different walls (the test could fail).
  EXPECT_FALSE(sameBits(alone[0][0][shard[0]].mean_gap_m, alone[1][0][shard[0]].mean_gap_m));
}

TEST(SealingModel, AnImageOlderThanTheLeakageInForceIsRefused) {
  const PixelGrid g = grid(96, 96);
  const auto m = model(g);
  std::vector<std::size_t> all(m.segmentCount());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
  SealingState state = m.initialState(all);
  const DepthGrid first = randomSurface(g, 1), second = randomSurface(g, 2);
  m.step(state, {&first, -0.05}, 20'000'000, 10'000'000);
  EXPECT_EQ(state.t_ns, 20'000'000);
  const auto before = state.leaks;
  EXPECT_THROW(m.step(state, {&second, -0.05}, 10'000'000, 10'000'000), std::invalid_argument);
  for (std::size_t s = 0; s < all.size(); ++s) EXPECT_TRUE(sameBits(state.leaks[s].leak_area_m2, before[s].leak_area_m2));
  // The same time again (a held image) and a later one are taken.
  m.step(state, {&second, -0.05}, 20'000'000, 10'000'000);
  m.step(state, {&first, -0.05}, 30'000'000, 10'000'000);
  EXPECT_EQ(state.computed, 3u);
}

TEST(SealingNode, BadDepthImagesAreDroppedCountedAndTheLastValidLeakageHeld) {
  const PixelGrid g = grid(128, 128);
  const auto m = model(g);
  SealingNode node(m, ShardSpec{0, 1});
  // Before any image: the closed sealing.
  const auto initial = node.step({});
  ASSERT_EQ(initial.segments().size(), m.segmentCount());
  for (std::size_t s = 0; s < m.segmentCount(); ++s) {
    EXPECT_EQ(initial.segments()[s].leak_area_m2(), m.closedLeaks()[s].leak_area_m2);
  }
  DepthGrid cracked = flatWall(g);
  addCrack(cracked, Crack{0, 0, 0.2, 0.01, 0.03, 0, 1e9});
  const auto good = node.step({image(cracked, 1)});
  EXPECT_EQ(node.computed(), 1u);

  auto nan = image(cracked, 2);
  nan.height_m()[77] = std::numeric_limits<float>::quiet_NaN();
  auto small = image(flatWall(grid(64, 64)), 3);
  auto scaled = image(flatWall(g), 4);
  scaled.pixel_size_m(0.001);
  auto short_data = image(flatWall(g), 5);
  short_data.height_m().pop_back();
  auto out_of_range = image(flatWall(g), 6);
  out_of_range.height_m()[5] = 0.2f;
  auto inverted = image(flatWall(g), 7);
  inverted.near_m(-0.05);
  inverted.far_m(0.05);
  std::uint64_t expected_drops = 0;
  for (const auto& bad : {nan, small, scaled, short_data, out_of_range, inverted}) {
    EXPECT_FALSE(checkDepthImage(bad, g).empty());
    const auto held = node.step({bad});
    EXPECT_EQ(node.dropped(), ++expected_drops);
    ASSERT_EQ(held.segments().size(), good.segments().size());
    for (std::size_t s = 0; s < held.segments().size(); ++s) {
      EXPECT_TRUE(sameBits(held.segments()[s].leak_area_m2(), good.segments()[s].leak_area_m2()));
    }
  }
  EXPECT_EQ(node.computed(), 1u);
  // A valid image after bad ones is computed again.
  node.step({nan, image(flatWall(g), 8)});
  EXPECT_EQ(node.computed(), 2u);
  EXPECT_EQ(node.leaks()[0].leak_area_m2, m.closedLeaks()[0].leak_area_m2);
}

TEST(SealingNode, ASegmentOverNothingIsMarkedAndNamedOnce) {
  // The robot stands with its right third past the edge of the scene: the camera sees no
  // wall there (far). Those segments leak like an open gap, and say so.
  const PixelGrid g = grid(128, 128);
  const auto m = model(g);
  SealingNode node(m, ShardSpec{0, 1});
  DepthGrid edge = flatWall(g);
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 2 * g.width_px / 3; c < g.width_px; ++c) edge.height_m[r * g.width_px + c] = -0.05f;
  }
  auto sample = image(edge, 1);
  sample.t_ns(1'250'000'000);
  const auto leak = node.step({sample});
  std::size_t over_nothing = 0, on_wall = 0;
  for (std::size_t s = 0; s < m.segmentCount(); ++s) {
    const double share = leak.segments()[s].no_surface_share();
    EXPECT_GE(share, 0.0);
    EXPECT_LE(share, 1.0);
    if (share >= SealingNode::kNoSurfaceWarnShare) {
      ++over_nothing;
      EXPECT_GT(leak.segments()[s].leak_area_m2(), 10.0 * m.closedLeaks()[s].leak_area_m2)
          << m.params().segment_names[s] << ": over nothing, an open gap";
    } else if (share == 0.0) {
      ++on_wall;
    }
  }
  EXPECT_GT(over_nothing, 0u);
  EXPECT_GT(on_wall, 0u) << "the left part stands on the wall";
  EXPECT_EQ(node.noSurfaceWarned().size(), over_nothing) << "each named once";
  auto again = image(edge, 5);
  again.t_ns(1'300'000'000);
  node.step({again});
  EXPECT_EQ(node.noSurfaceWarned().size(), over_nothing) << "and only once";
  // Back on the wall: the share goes back to 0.
  auto wall = image(flatWall(g), 9);
  wall.t_ns(1'400'000'000);
  const auto back = node.step({wall});
  for (const auto& segment : back.segments()) EXPECT_EQ(segment.no_surface_share(), 0.0);
}

TEST(SealingNode, PicturesAreTwoPngsOfTheCameraSizeOnceAnImageWasComputed) {
  const PixelGrid g = PixelGrid{128, 128, 0.8 / 128};
  const auto m = model(g);
  SealingNode node(m, ShardSpec{1, 2});
  EXPECT_TRUE(node.pictures().empty());
  node.step({image(randomSurface(g, 3), 1)});
  const auto pictures = node.pictures();
  ASSERT_EQ(pictures.size(), 2u);
  EXPECT_EQ(pictures[0].first, "edges");
  EXPECT_EQ(pictures[1].first, "gaps");
  for (const auto& [kind, png] : pictures) {
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(std::memcmp(png.data(), "\x89PNG", 4), 0) << kind;
    const auto sample = sealingImageToIdl("sealing", 1, 5, kind, png);
    EXPECT_EQ(sample.png().size(), png.size());
  }
}

TEST(SealingTranslate, DepthImageRoundTripsAndLeakageCarriesTheSegmentsAsked) {
  const PixelGrid g = grid(100, 120);
  DepthGrid depth = flatWall(g, 0.001f);
  depth.height_m[17] = -0.02f;
  const auto back = depthGridFromIdl(depthImageToIdl(depth, -0.05, 0.05));
  EXPECT_EQ(back.grid, g);
  EXPECT_EQ(back.height_m, depth.height_m);
  std::vector<SegmentLeak> leaks(3);
  leaks[2].leak_area_m2 = 1.5e-5;
  leaks[2].mean_gap_m = 1e-4;
  const auto sample = leakageToIdl({"a", "b", "c"}, leaks, {2, 0});
  ASSERT_EQ(sample.segments().size(), 2u);
  EXPECT_EQ(sample.segments()[0].segment(), "c");
  EXPECT_EQ(sample.segments()[0].leak_area_m2(), 1.5e-5);
  EXPECT_EQ(sample.segments()[0].mean_gap_m(), 1e-4);
  EXPECT_EQ(sample.segments()[1].segment(), "a");
}

TEST(SealingTranslate, TheOnePassCheckRefusesExactlyThePixelsOutsideTheRangeInDouble) {
  // The check screens in float; each pixel must be refused exactly when, in double, it is not
  // finite or lies outside [far - 1 µm, near + 1 µm]: try the floats around both bounds.
  const PixelGrid g = grid(16, 16);
  for (const auto& [far_m, near_m] : {std::pair{-0.05, 0.05}, std::pair{-0.3, 0.0125}, std::pair{-1.0 / 3, 0.1}}) {
    const double low_m = far_m - 1e-6;
    const double high_m = near_m + 1e-6;
    std::vector<float> candidates{std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                                  -std::numeric_limits<float>::infinity(), 0.0f};
    for (const double bound : {low_m, high_m, far_m, near_m}) {
      float v = static_cast<float>(bound);
      for (int k = 0; k < 3; ++k) v = std::nextafter(v, -1.0f);
      for (int k = 0; k < 7; ++k, v = std::nextafter(v, 1.0f)) candidates.push_back(v);
    }
    for (const float v : candidates) {
      DepthGrid depth = flatWall(g, 0.0f);
      auto sample = depthImageToIdl(depth, far_m, near_m);
      sample.height_m()[37] = v;
      const bool valid = std::isfinite(v) && !(v < low_m) && !(v > high_m);
      float highest = -1.0f;
      const std::string why = checkDepthImage(sample, g, &highest);
      EXPECT_EQ(why.empty(), valid) << v << " in [" << far_m << ", " << near_m << "]: " << why;
      if (valid) {
        EXPECT_EQ(highest, std::max(0.0f, v));
      } else {
        EXPECT_NE(why.find("row 2, col 5"), std::string::npos) << why;  // pixel 37 of 16 columns
      }
    }
  }
}

TEST(SealingTranslate, TheOnePassCheckFindsABadPixelAndTheHighestWhereverTheyLie) {
  // The screen takes 16 values at a time and the rest one by one: a bad or the highest pixel
  // at every position of an image whose size is no multiple of 16 (17 x 17 = 18 x 16 + 1).
  const PixelGrid g = grid(17, 17);
  for (std::size_t at = 0; at < g.pixelCount(); ++at) {
    auto sample = depthImageToIdl(flatWall(g, -0.01f), -0.05, 0.05);
    sample.height_m()[at] = 0.03f;
    float highest = 0.0f;
    ASSERT_EQ(checkDepthImage(sample, g, &highest), "") << at;
    EXPECT_EQ(highest, 0.03f) << at;
    sample.height_m()[at] = std::numeric_limits<float>::quiet_NaN();
    const std::string why = checkDepthImage(sample, g, &highest);
    const std::string where = "row " + std::to_string(at / 17) + ", col " + std::to_string(at % 17);
    EXPECT_NE(why.find(where), std::string::npos) << at << ": " << why;
    sample.height_m()[at] = 0.06f;  // above near
    EXPECT_NE(checkDepthImage(sample, g).find(where), std::string::npos) << at;
  }
}

TEST(SealingTranslate, TakingTheImagesPixelsGivesTheGridCopyingThemGives) {
  const PixelGrid g = grid(40, 30);
  DepthGrid depth = flatWall(g, 0.001f);
  depth.height_m[17] = -0.02f;
  depth.height_m[401] = 0.03f;
  auto whole = depthImageToIdl(depth, -0.05, 0.05);
  // A tile: rows 3..12, columns 5..24 of the image.
  climbsim::DepthImage tile = whole;
  tile.tile_row0(3);
  tile.tile_col0(5);
  tile.tile_rows(10);
  tile.tile_cols(20);
  tile.height_m().clear();
  for (int r = 3; r < 13; ++r) {
    for (int c = 5; c < 25; ++c) tile.height_m().push_back(depth.height_m[static_cast<std::size_t>(r) * 40 + c]);
  }
  for (const auto* sample : {&whole, &tile}) {
    const DepthGrid copied = depthGridFromIdl(*sample);
    float highest = 0.0f;
    ASSERT_EQ(checkDepthImage(*sample, g, &highest), "");
    EXPECT_EQ(static_cast<double>(highest), copied.upper_bound_m);
    DepthGrid taken;
    depthGridFromIdl(climbsim::DepthImage(*sample), taken, highest);
    EXPECT_EQ(taken.grid, copied.grid);
    EXPECT_EQ(taken.height_m, copied.height_m);
    EXPECT_EQ(taken.upper_bound_m, copied.upper_bound_m);
  }
}

TEST(SealingTranslate, SupportHeightsTravelWithTheImageBoundItAndBadOnesAreNamed) {
  const PixelGrid g = grid(40, 30);
  DepthGrid depth = flatWall(g, -0.01f);
  depth.supports.raster = {41, 42, 407};
  depth.supports.height_m = {-0.004f, 0.002f, 0.0f};
  const auto sample = depthImageToIdl(depth, -0.05, 0.05);
  float highest = 0.0f;
  ASSERT_EQ(checkDepthImage(sample, g, &highest), "");
  EXPECT_EQ(highest, 0.002f);  // a support above every pixel bounds the image
  const DepthGrid back = depthGridFromIdl(sample);
  EXPECT_EQ(back.supports.raster, depth.supports.raster);
  EXPECT_EQ(back.supports.height_m, depth.supports.height_m);
  EXPECT_EQ(back.upper_bound_m, 0.002f);
  EXPECT_EQ(checkDepthGrid(back, g), "");
  // Each bad support named: not ascending, outside the tile, above near, fewer heights.
  auto unordered = sample;
  unordered.support_px({42, 41, 407});
  EXPECT_NE(checkDepthImage(unordered, g).find("support_px[1] = 41"), std::string::npos);
  auto outside = sample;
  outside.support_px({41, 42, 1200});
  EXPECT_NE(checkDepthImage(outside, g).find("support_px[2] = 1200"), std::string::npos);
  auto high = sample;
  high.support_m({-0.004f, 0.2f, 0.0f});
  EXPECT_NE(checkDepthImage(high, g).find("row 1, col 2) support_m = 0.2"), std::string::npos)
      << checkDepthImage(high, g);
  auto fewer = sample;
  fewer.support_m({0.0f});
  EXPECT_NE(checkDepthImage(fewer, g).find("3 support pixels with 1 support heights"), std::string::npos);
  DepthGrid bad = back;
  bad.supports.height_m[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(checkDepthGrid(bad, g).find("support_m[1]"), std::string::npos);
}

}  // namespace
}  // namespace climbsim::sealing::testing
