// Depth tiles (issue 14): `climbsim-scene --tile I/N` renders exactly the whole image's pixels
// at the pixels shard I can read (the tile's mask; far at the box's others), and a sealing
// shard fed only its tile gives the leakage it gives with the whole image, bit for bit, on the
// shipped pylon scene.

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

TEST(ShardTile, AShardThatGetsOnlyAnotherShardsTileSaysWhichPixelsItNeeds) {
  const int px = 256;
  SceneNodeOptions options;
  options.depth_size_px = px;
  options.depth_width_m = 0.8;
  SceneNode node(loadScene(kPylon), options);
  node.setDepthTile(shardTile("1/2", kRobot, node.camera()));
  node.applyRobotStates({poses()[0]});
  auto sample = depthImageToIdl(node.renderDepth());
  sample.source("scene-tile-1");
  const RobotDescription robot = loadRobotDescription(kRobot);
  const RobotGeometry geometry = computeGeometry(robot);
  const sealing::SealingModel model(sealing::sealingParamsFromRobot(robot, geometry), geometry,
                                    sealing::PixelGrid{px, px, 0.8 / px}, kRobot);
  sealing::SealingNode shard0(model, sealing::ShardSpec{0, 2});
  try {
    shard0.step({sample});
    FAIL() << "shard 0 accepted shard 1's tile";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sealing shard 0/2 needs rows"), std::string::npos) << what;
    EXPECT_NE(what.find("'scene-tile-1' rows"), std::string::npos) << what;
  }
  EXPECT_THROW(shardTile("2/2", kRobot, node.camera()), ConfigError);
  EXPECT_THROW(shardTile("0/19", kRobot, node.camera()), ConfigError);
}

}  // namespace
}  // namespace climbsim::scene
