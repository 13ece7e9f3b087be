// Depth tiles (sharded sealing): `climbsim-scene --tile I/N` renders exactly the whole image's
// pixels at the pixels shard I can read (the tile's mask; far at the box's others) and sends only
// those (mask runs), and a sealing shard fed only its tile gives the leakage it gives with the
// whole image, bit for bit, on the shipped pylon scene.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "scene_node.hpp"
#include "scene_translate.hpp"
#include "sealing_node.hpp"
#include "sealing_translate.hpp"
#include "shard_tile.hpp"

namespace climbsim::scene {
namespace {

const std::string kPylon = std::string(CLIMBSIM_BUILD_DIR) + "/scenes/pylon.xml";
const std::string kRobot = std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml";

climbsim::RobotState stateAt(double x, double y, double yaw_deg) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  auto s = robotStateToIdl(T);
  s.source("drive");
  return s;
}

/// Poses on the pylon: the scenarios' starts and the crack-descent crack under the robot.
const std::vector<climbsim::RobotState>& poses() {
  static const std::vector<climbsim::RobotState> all{stateAt(1.0, 1.2, -90), stateAt(1.0, 0.75, -90),
                                                     stateAt(1.0, 0.95, -80), stateAt(2.3, 1.6, 30)};
  return all;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ShardTile, ATileHoldsTheWholeImagesPixelsBitForBit) {
  ASSERT_TRUE(std::filesystem::exists(kPylon)) << kPylon << " (generated at build time)";
  for (const int px : {256, 1024}) {
    SceneNodeOptions whole_options;
    whole_options.depth_size_px = px;
    whole_options.depth_width_m = 0.8;
    SceneNode node(loadScene(kPylon), whole_options);
    for (const auto& pose : poses()) {
      node.applyRobotStates({pose});
      node.setDepthTile(PixelTile{});
      const DepthImage a = node.renderDepth();
      for (const std::size_t n : {1u, 2u, 3u, 4u}) {
        for (std::size_t i = 0; i < n; ++i) {
          const PixelTile t = shardTile(std::to_string(i) + "/" + std::to_string(n), kRobot, node.camera());
          ASSERT_FALSE(t.whole());
          node.setDepthTile(t);
          const DepthImage b = node.renderDepth();
          ASSERT_EQ(b.tile, t);
          ASSERT_EQ(b.height_m.size(), static_cast<std::size_t>(t.rows) * t.cols);
          ASSERT_TRUE(t.mask);
          std::size_t in_mask = 0;
          for (int r = t.row0; r < t.row0 + t.rows; ++r) {
            for (int c = t.col0; c < t.col0 + t.cols; ++c) {
              // The shard's pixels as in the whole image, the rest of the box far (not rendered).
              const float expected = t.mask->contains(r, c) ? a.at(r, c) : static_cast<float>(a.far_m);
              in_mask += t.mask->contains(r, c);
              ASSERT_TRUE(sameBits(expected, b.at(r, c)))
                  << px << " px, tile " << i << "/" << n << ", pixel " << r << "," << c << " (in mask "
                  << t.mask->contains(r, c) << "): " << a.at(r, c) << " vs " << b.at(r, c);
            }
          }
          ASSERT_EQ(in_mask, t.mask->count()) << "every pixel of the mask lies in the box";
        }
      }
    }
  }
}

TEST(ShardTile, TilesShrinkWithTheShardCountAndAShardFedItsTileGivesTheWholeImagesLeakage) {
  const int px = 512;
  SceneNodeOptions whole_options;
  whole_options.depth_size_px = px;
  whole_options.depth_width_m = 0.8;
  SceneNode node(loadScene(kPylon), whole_options);
  const RobotDescription robot = loadRobotDescription(kRobot);
  const RobotGeometry geometry = computeGeometry(robot);
  const sealing::PixelGrid grid{px, px, 0.8 / px};
  const sealing::SealingModel model(sealing::sealingParamsFromRobot(robot, geometry), geometry, grid, kRobot);
  for (const std::size_t n : {2u, 3u, 4u}) {
    std::size_t tile_pixels = 0;
    for (std::size_t i = 0; i < n; ++i) {
      node.setDepthTile(PixelTile{});
      const PixelTile tile = shardTile(std::to_string(i) + "/" + std::to_string(n), kRobot, node.camera());
      tile_pixels += static_cast<std::size_t>(tile.rows) * tile.cols;
      sealing::SealingNode from_whole(model, sealing::ShardSpec{i, n});
      sealing::SealingNode from_tile(model, sealing::ShardSpec{i, n});
      for (const auto& pose : poses()) {
        node.applyRobotStates({pose});
        node.setDepthTile(PixelTile{});
        auto whole_sample = depthImageToIdl(node.renderDepth());
        node.setDepthTile(tile);
        auto tile_sample = depthImageToIdl(node.renderDepth());
        tile_sample.source("scene-tile");
        const auto a = from_whole.step({whole_sample});
        const auto b = from_tile.step({tile_sample});
        ASSERT_EQ(a.segments().size(), b.segments().size());
        for (std::size_t s = 0; s < a.segments().size(); ++s) {
          const double x = a.segments()[s].leak_area_m2();
          const double y = b.segments()[s].leak_area_m2();
          ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << n << " shards, shard " << i << ", segment " << s;
        }
      }
    }
    // N tiles together hold less than N whole images (what crosses the network per frame).
    EXPECT_LT(static_cast<double>(tile_pixels), 0.85 * n * px * px) << n << " shards";
  }
}

/// The shard model of a px x px camera over 0.8 m.
sealing::SealingModel modelOf(int px, sealing::StripOutline outline = sealing::StripOutline::kPixelCentres) {
  const RobotDescription robot = loadRobotDescription(kRobot);
  const RobotGeometry geometry = computeGeometry(robot);
  sealing::SealingParams params = sealing::sealingParamsFromRobot(robot, geometry);
  params.strip_outline = outline;
  return sealing::SealingModel(params, geometry, sealing::PixelGrid{px, px, 0.8 / px}, kRobot);
}

/// What shard `spec` of `model` says when it refuses `sample` as its first image ("" if it took it).
std::string refusal(const sealing::SealingModel& model, const sealing::ShardSpec& spec,
                    const climbsim::DepthImage& sample) {
  sealing::SealingNode node(model, spec);
  try {
    node.step({sample});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

/// The DepthImage sample of shard `shard`'s ("I/N") tile of a px x px camera over 0.8 m at `pose`.
climbsim::DepthImage tileSample(int px, const std::string& shard, const climbsim::RobotState& pose) {
  SceneNodeOptions options;
  options.depth_size_px = px;
  options.depth_width_m = 0.8;
  SceneNode node(loadScene(kPylon), options);
  node.setDepthTile(shardTile(shard, kRobot, node.camera()));
  node.applyRobotStates({pose});
  return depthImageToIdl(node.renderDepth());
}

TEST(ShardTile, AShardThatGetsOnlyAnotherShardsTileSaysWhichPixelsItNeeds) {
  const int px = 256;
  auto sample = tileSample(px, "1/2", poses()[0]);
  sample.source("scene-tile-1");
  const sealing::SealingModel model = modelOf(px);
  const std::string what = refusal(model, sealing::ShardSpec{0, 2}, sample);
  EXPECT_NE(what.find("sealing shard 0/2 needs rows"), std::string::npos) << what;
  EXPECT_NE(what.find("'scene-tile-1' rows"), std::string::npos) << what;
  SceneNodeOptions options;
  options.depth_size_px = px;
  options.depth_width_m = 0.8;
  const SceneNode node(loadScene(kPylon), options);
  EXPECT_THROW(shardTile("2/2", kRobot, node.camera()), ConfigError);
  EXPECT_THROW(shardTile("0/19", kRobot, node.camera()), ConfigError);
}

TEST(ShardTile, AMaskedTileSendsOnlyTheShardsPixelsAsRowRunsAndTheShardPlacesThemAsTheWholeImageHasThem) {
  const int px = 1024;
  SceneNodeOptions options;
  options.depth_size_px = px;
  options.depth_width_m = 0.8;
  SceneNode node(loadScene(kPylon), options);
  node.applyRobotStates({poses()[1]});  // the crack under the robot
  const DepthImage whole = node.renderDepth();
  const sealing::SealingModel model = modelOf(px);
  for (const char* shard : {"0/1", "0/2", "1/2", "2/4"}) {
    const PixelTile tile = shardTile(shard, kRobot, node.camera());
    node.setDepthTile(tile);
    const climbsim::DepthImage sample = depthImageToIdl(node.renderDepth());
    node.setDepthTile(PixelTile{});
    const auto& runs = sample.mask_runs();
    ASSERT_FALSE(runs.empty()) << shard;
    std::size_t pixels = 0;
    const sealing::PixelBox box = sealing::tileOf(sample);
    ASSERT_EQ(sealing::checkMaskRuns(runs, px, box, &pixels), "") << shard;
    // Exactly the mask's pixels, each once, each the whole image's value bit for bit.
    EXPECT_EQ(pixels, tile.mask->count()) << shard;
    ASSERT_EQ(sample.height_m().size(), pixels) << shard;
    for (std::size_t i = 0; i < pixels; ++i) {
      const std::size_t raster = sealing::rasterOfValue(sample, box, i);
      const int r = static_cast<int>(raster / px), c = static_cast<int>(raster % px);
      ASSERT_TRUE(tile.mask->contains(r, c)) << shard << " value " << i << " at " << r << "," << c;
      ASSERT_TRUE(sameBits(sample.height_m()[i], whole.at(r, c))) << shard << " pixel " << r << "," << c;
    }
    // A small part of the box crosses the network, and the checks pass on it.
    EXPECT_LT(static_cast<double>(pixels), 0.5 * box.rows * box.cols) << shard;
    float highest = 0.0f;
    ASSERT_EQ(sealing::checkDepthImage(sample, model.grid(), &highest), "") << shard;
    // Placed into the shard's image: its pixels where the whole image has them, far elsewhere.
    sealing::DepthGrid placed;
    sealing::depthGridFromIdl(sample, placed);
    ASSERT_EQ(placed.height_m.size(), static_cast<std::size_t>(px) * px);
    EXPECT_EQ(placed.upper_bound_m, highest);
    for (int r = 0; r < px; ++r) {
      for (int c = 0; c < px; ++c) {
        const float expected = tile.mask->contains(r, c) ? whole.at(r, c) : static_cast<float>(sample.far_m());
        ASSERT_TRUE(sameBits(placed.height_m[static_cast<std::size_t>(r) * px + c], expected))
            << shard << " pixel " << r << "," << c;
      }
    }
    // What the shard reads is what the renderer sends.
    sealing::ShardSpec spec = sealing::ShardSpec::parse(shard);
    EXPECT_TRUE(sealing::maskRunsCover(runs, model.neededPixels(spec.segments(model.masks()), sample.near_m() + 1e-6)));
  }
}

TEST(ShardTile, EachFramesTileForItsGeometrysHeightBoundIsSmallerHoldsTheBoundAndGivesTheWholeImagesLeakage) {
  const int px = 1024;
  SceneNodeOptions options;
  options.depth_size_px = px;
  options.depth_width_m = 0.8;
  SceneNode whole_node(loadScene(kPylon), options);
  const sealing::SealingModel model = modelOf(px);
  for (const std::size_t n : {2u, 4u}) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::string shard = std::to_string(i) + "/" + std::to_string(n);
      auto tiles = std::make_shared<ShardTiles>(shard, kRobot, whole_node.camera());
      SceneNodeOptions tiled = options;
      tiled.depth_tile_for_bound = [tiles](double bound_m) { return tiles->forBound(bound_m); };
      SceneNode node(loadScene(kPylon), tiled);
      sealing::SealingNode from_whole(model, sealing::ShardSpec{i, n});
      sealing::SealingNode from_tile(model, sealing::ShardSpec{i, n});
      for (const auto& pose : poses()) {
        whole_node.applyRobotStates({pose});
        node.applyRobotStates({pose});
        const DepthImage whole = whole_node.renderDepth();
        const DepthImage image = node.renderDepth();
        // The bound from the leaves' boxes holds every pixel of the whole image, and on the
        // pylon (heights of millimetres) it lies well below the camera's near plane.
        const double bound_m = image.near_m - image.headroom_m;
        EXPECT_GT(image.headroom_m, 0.02) << shard;
        EXPECT_EQ(whole.headroom_m, 0.0);
        for (const float h : whole.height_m) ASSERT_LE(h, bound_m) << shard;
        // Fewer pixels than the tile for the near plane, each the whole image's.
        const auto sample = depthImageToIdl(image);
        EXPECT_EQ(sample.headroom_m(), image.headroom_m);
        EXPECT_LT(static_cast<double>(sample.height_m().size()), 0.8 * tiles->forNear().mask->count()) << shard;
        const sealing::PixelBox box = sealing::tileOf(sample);
        for (std::size_t k = 0; k < sample.height_m().size(); ++k) {
          const std::size_t raster = sealing::rasterOfValue(sample, box, k);
          ASSERT_TRUE(sameBits(sample.height_m()[k], whole.height_m[raster])) << shard << " pixel " << raster;
        }
        // The shard's leakage from it is the one from the whole image, bit for bit.
        auto whole_sample = depthImageToIdl(whole);
        const auto a = from_whole.step({whole_sample});
        const auto b = from_tile.step({sample});
        ASSERT_EQ(from_tile.dropped(), 0u) << shard;
        ASSERT_EQ(a.segments().size(), b.segments().size());
        for (std::size_t s = 0; s < a.segments().size(); ++s) {
          const double x = a.segments()[s].leak_area_m2(), y = b.segments()[s].leak_area_m2();
          ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << shard << " segment " << s;
        }
      }
    }
  }
}

TEST(ShardTile, WithSubpixelLeakageEachShardsTileGivesTheWholeSealingsLeakageBitForBit) {
  // depth_camera.subpixel: area-weighted edge pixels in every renderer, sub-pixel strip shares
  // in every shard and in each renderer's tiles, and support heights for the robot's max slope.
  // A shard fed its renderer's tiles gets the whole image's pixels and supports and gives each
  // of its segments the numbers the whole sealing gives them from the whole image.
  const int px = 256;
  const sealing::SealingModel model = modelOf(px, sealing::StripOutline::kSubpixelShares);
  SceneNodeOptions options;
  options.depth_size_px = px;
  options.depth_width_m = 0.8;
  options.depth_samples_per_pixel = kSubpixelDepthSamplesPerPixel;
  options.depth_support_slope = model.params().max_slope;
  SceneNode whole_node(loadScene(kPylon), options);
  std::size_t supports = 0;
  sealing::SealingNode whole_sealing(model, sealing::ShardSpec{0, 1});
  for (const std::size_t n : {2u, 3u}) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::string shard = std::to_string(i) + "/" + std::to_string(n);
      auto tiles = std::make_shared<ShardTiles>(shard, kRobot, whole_node.camera(), true);
      SceneNodeOptions tiled = options;
      tiled.depth_tile_for_bound = [tiles](double bound_m) { return tiles->forBound(bound_m); };
      SceneNode node(loadScene(kPylon), tiled);
      sealing::SealingNode from_tile(model, sealing::ShardSpec{i, n});
      for (const auto& pose : poses()) {
        whole_node.applyRobotStates({pose});
        node.applyRobotStates({pose});
        const DepthImage whole = whole_node.renderDepth();
        const auto sample = depthImageToIdl(node.renderDepth());
        const sealing::PixelBox box = sealing::tileOf(sample);
        std::vector<bool> sent(whole.height_m.size(), false);
        for (std::size_t k = 0; k < sample.height_m().size(); ++k) {
          const std::size_t raster = sealing::rasterOfValue(sample, box, k);
          sent[raster] = true;
          ASSERT_TRUE(sameBits(sample.height_m()[k], whole.height_m[raster])) << shard << " pixel " << raster;
        }
        std::vector<std::uint32_t> want_px;
        std::vector<float> want_m;
        for (std::size_t k = 0; k < whole.support_px.size(); ++k) {
          if (!sent[whole.support_px[k]]) continue;
          want_px.push_back(whole.support_px[k]);
          want_m.push_back(whole.support_m[k]);
        }
        ASSERT_EQ(sample.support_px(), want_px) << shard;
        for (std::size_t k = 0; k < want_m.size(); ++k) ASSERT_TRUE(sameBits(sample.support_m()[k], want_m[k])) << shard;
        supports += want_px.size();
        const auto all = whole_sealing.step({depthImageToIdl(whole)});
        const auto mine = from_tile.step({sample});
        ASSERT_EQ(from_tile.dropped(), 0u) << shard;
        ASSERT_FALSE(mine.segments().empty()) << shard;
        for (const auto& segment : mine.segments()) {
          bool found = false;
          for (const auto& reference : all.segments()) {
            if (reference.segment() != segment.segment()) continue;
            found = true;
            const double x = reference.leak_area_m2(), y = segment.leak_area_m2();
            ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << shard << " segment " << segment.segment();
          }
          ASSERT_TRUE(found) << shard << " segment " << segment.segment();
        }
      }
    }
  }
  EXPECT_GT(supports, 0u) << "no shard's tile carried a support height";
}

TEST(ShardTile, APixelAboveTheSamplesHeightBoundOrABadHeadroomIsNamedInOneLine) {
  const int px = 256;
  const auto good = tileSample(px, "0/2", poses()[0]);
  const sealing::SealingModel model = modelOf(px);
  const auto why = [&](const climbsim::DepthImage& sample) { return sealing::checkDepthImage(sample, model.grid()); };
  {
    auto bad = good;  // a bound below the first pixel
    bad.headroom_m(bad.near_m() - bad.height_m()[0] + 1e-3);
    const std::string text = why(bad);
    EXPECT_NE(text.find("outside [far_m, near_m - headroom_m] = ["), std::string::npos) << text;
  }
  for (const double headroom : {-1e-3, std::nan(""), 0.2}) {
    auto bad = good;
    bad.headroom_m(headroom);
    EXPECT_EQ(why(bad).rfind("headroom_m = ", 0), 0u) << why(bad);
    EXPECT_NE(why(bad).find("(need 0 <= headroom_m <= near_m - far_m = "), std::string::npos) << why(bad);
  }
}

TEST(ShardTile, AMaskedTileWhoseBoxHoldsTheShardsBoxButNotItsPixelsIsPassedOverNamingIt) {
  const int px = 256;
  auto sample = tileSample(px, "1/2", poses()[0]);
  // Shard 1's pixels, in a box as large as the image: the box holds shard 0's box, the pixels
  // do not (a check of the box alone would pass it).
  sample.source("scene-1");
  sample.tile_row0(0);
  sample.tile_col0(0);
  sample.tile_rows(px);
  sample.tile_cols(px);
  const sealing::SealingModel model = modelOf(px);
  const std::string what = refusal(model, sealing::ShardSpec{0, 2}, sample);
  EXPECT_NE(what.find("'scene-1' rows 0+256 cols 0+256 masked to other pixels"), std::string::npos)
      << "shard 0 computed shard 1's pixels: " << what;
  // The shard it was rendered for takes it.
  sealing::SealingNode shard1(model, sealing::ShardSpec{1, 2});
  EXPECT_NO_THROW(shard1.step({sample}));
  EXPECT_EQ(shard1.computed(), 1u);
}

TEST(ShardTile, BadMaskRunsAndBadPixelsOfAMaskedTileAreNamedInOneLine) {
  const int px = 256;
  const auto good = tileSample(px, "0/2", poses()[0]);
  const sealing::SealingModel model = modelOf(px);
  const auto why = [&](const climbsim::DepthImage& sample) { return sealing::checkDepthImage(sample, model.grid()); };
  ASSERT_EQ(why(good), "");
  const auto& runs = good.mask_runs();
  const std::size_t row0 = runs[0] / px;
  {
    auto bad = good;
    bad.mask_runs().pop_back();
    EXPECT_EQ(why(bad), "mask_runs holds " + std::to_string(runs.size() - 1) + " values (a start and a length per run)");
  }
  {
    auto bad = good;  // the first run reaches past its row
    bad.mask_runs()[1] = px;
    const std::string text = why(bad);
    EXPECT_EQ(text.rfind("mask run 0 (mask_runs[0] = " + std::to_string(runs[0]) + ", length 256: row " +
                             std::to_string(row0),
                         0),
              0u)
        << text;
    EXPECT_NE(text.find("does not lie along one row of the tile rows "), std::string::npos) << text;
  }
  {
    auto bad = good;  // the second run starts inside the first
    bad.mask_runs()[2] = runs[0];
    bad.mask_runs()[3] = 1;
    EXPECT_NE(why(bad).find("mask run 1 (mask_runs[2] = " + std::to_string(runs[0]) + ", length 1"),
              std::string::npos)
        << why(bad);
    EXPECT_NE(why(bad).find("overlaps or precedes the run before it"), std::string::npos) << why(bad);
  }
  {
    auto bad = good;  // a value too few
    bad.height_m().pop_back();
    EXPECT_EQ(why(bad), std::to_string(good.height_m().size() - 1) + " heights for " + std::to_string(runs.size() / 2) +
                            " mask runs of " + std::to_string(good.height_m().size()) + " px");
  }
  {
    auto bad = good;  // the first value of the second run: its pixel is named
    bad.height_m()[runs[1]] = std::nanf("");
    const std::string text = why(bad);
    EXPECT_NE(text.find("pixel (row " + std::to_string(runs[2] / px) + ", col " + std::to_string(runs[2] % px) + ")"),
              std::string::npos)
        << text;
  }
  {
    auto bad = good;
    bad.height_m()[runs[1]] = 1.0f;  // far above near
    const std::string text = why(bad);
    EXPECT_EQ(text.rfind("pixel (row " + std::to_string(runs[2] / px) + ", col " + std::to_string(runs[2] % px) +
                             ") height_m = 1 outside",
                         0),
              0u)
        << text;
  }
  // A shard drops such a sample, counts it and holds its leakage (the sample is not taken
  // for another shard's tile).
  sealing::SealingNode shard0(model, sealing::ShardSpec{0, 2});
  auto bad = good;
  bad.mask_runs()[1] = px;
  EXPECT_NO_THROW(shard0.step({bad}));
  EXPECT_EQ(shard0.dropped(), 1u);
  EXPECT_EQ(shard0.computed(), 0u);
}

TEST(ShardTile, TheDefaultRunsFramesAreTheWholeSealingsPixelsButTheFramesReadWholeAndGiveTheSameLeakage) {
  // A scenario run's scene (DepthFrameChoice from configureScene): 50 frames/s, the clock's step
  // 5 ms, a sealing picture at 0.13 s (read at 0.145 s: the frame of 0.14 s).
  SceneNodeOptions options;
  options.depth_size_px = 256;
  options.depth_width_m = 0.8;
  DepthFrameChoice choice;
  choice.robot_file = kRobot;
  choice.read_at_s = {0.13};
  choice.read_lag_ns = 5'000'000;
  SceneNode whole_node(loadScene(kPylon), options);
  SceneNode node(loadScene(kPylon), options, choice);
  const sealing::SealingModel model = modelOf(256);
  sealing::SealingNode from_whole(model, sealing::ShardSpec{0, 1});
  sealing::SealingNode from_default(model, sealing::ShardSpec{0, 1});
  DepthGridSchedule whole_grids, default_grids;
  std::vector<int> whole_frames;
  for (int k = 0; k < 12; ++k) {
    const std::int64_t t_ns = k * 20'000'000LL;
    const auto& pose = poses()[static_cast<std::size_t>(k) % poses().size()];
    whole_node.applyRobotStates({pose});
    node.applyRobotStates({pose});
    const DepthImage whole = whole_node.renderDepthAt(t_ns);
    const DepthImage image = node.renderDepthAt(t_ns);
    ASSERT_TRUE(whole.tile.whole()) << "no choice: every frame whole";
    ASSERT_EQ(node.lastDepthWhole(), image.tile.whole());
    if (image.tile.whole()) {
      whole_frames.push_back(k);
      ASSERT_EQ(std::memcmp(image.height_m.data(), whole.height_m.data(), whole.height_m.size() * sizeof(float)), 0);
    } else {
      // Only the sealing's pixels, each the whole image's.
      ASSERT_TRUE(image.tile.mask);
      EXPECT_LT(image.tile.mask->count(), whole.height_m.size() / 2);
      for (int r = image.tile.row0; r < image.tile.row0 + image.tile.rows; ++r) {
        for (int c = image.tile.col0; c < image.tile.col0 + image.tile.cols; ++c) {
          if (image.tile.mask->contains(r, c)) {
            ASSERT_TRUE(sameBits(image.at(r, c), whole.at(r, c))) << k;
          }
        }
      }
    }
    // The depth grid from the frames it is due at, as from the whole images.
    const auto a_grid = whole_grids.offer(whole, t_ns);
    const auto b_grid = default_grids.offer(image, t_ns);
    ASSERT_EQ(a_grid.has_value(), b_grid.has_value()) << k;
    if (a_grid) {
      EXPECT_EQ(a_grid->height_m(), b_grid->height_m()) << k;
    }
    // The whole sealing's leakage, bit for bit.
    const auto a = from_whole.step({depthImageToIdl(whole)});
    const auto b = from_default.step({depthImageToIdl(image)});
    ASSERT_EQ(from_default.dropped(), 0u);
    ASSERT_EQ(a.segments().size(), b.segments().size());
    for (std::size_t s = 0; s < a.segments().size(); ++s) {
      const double x = a.segments()[s].leak_area_m2(), y = b.segments()[s].leak_area_m2();
      ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << k << " segment " << s;
    }
  }
  EXPECT_EQ(whole_frames, (std::vector<int>{0, 5, 7, 10})) << "the grid's frames and the picture's";
}

}  // namespace
}  // namespace climbsim::scene
