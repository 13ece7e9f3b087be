#include "shard_tile.hpp"

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"
#include "climbsim/shard_tiles/shard_partition.hpp"
#include "climbsim/shard_tiles/shard_pixels.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::scene {

ShardTiles::ShardTiles(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera,
                       bool subpixel)
    : width_px_(camera.width_px), height_px_(camera.height_px), near_m_(camera.near_m) {
  sealing::ShardSpec spec;
  try {
    spec = sealing::ShardSpec::parse(shard_text);
  } catch (const ConfigError& e) {
    throw ConfigError("--tile" + std::string(e.what()).substr(std::string("--shard").size()));
  }
  const RobotDescription robot = loadRobotDescription(robot_file);
  const RobotGeometry geometry = computeGeometry(robot);
  const sealing::PixelGrid grid{camera.width_px, camera.height_px, camera.pixel_size_m};
  sealing::SealingParams params = sealing::sealingParamsFromRobot(robot, geometry);
  if (subpixel) params.strip_outline = sealing::StripOutline::kSubpixelShares;
  masks_ = std::make_unique<const sealing::StripMasks>(geometry, grid, robot_file, params.strip_outline);
  pixels_ = std::make_unique<const sealing::ShardPixels>(params, *masks_);
  segments_ = spec.segments(*masks_);
}

ShardTiles::~ShardTiles() = default;

PixelTile ShardTiles::forBound(double height_bound_m) {
  // As the shard does (SealingNode::neededBox): the bound plus the 1 µm it admits above it.
  const double upper_bound_m = height_bound_m + 1e-6;
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t count = pixels_->neededCount(segments_, upper_bound_m);
  auto found = by_count_.find(count);
  if (found == by_count_.end()) {
    const sealing::PixelBox box = pixels_->neededBox(segments_, upper_bound_m);
    PixelTile tile{box.row0, box.col0, box.rows, box.cols, nullptr};
    tile.mask = std::make_shared<const PixelMask>(width_px_, height_px_, pixels_->neededPixels(segments_, upper_bound_m));
    found = by_count_.emplace(count, tile).first;
  }
  return found->second;
}

std::function<PixelTile(double)> wholeSealingTiles(const std::string& robot_file, const DepthCameraParams& camera,
                                                   bool subpixel) {
  const auto tiles = std::make_shared<ShardTiles>("0/1", robot_file, camera, subpixel);
  return [tiles](double height_bound_m) { return tiles->forBound(height_bound_m); };
}

PixelTile shardTile(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera,
                    bool subpixel) {
  return ShardTiles(shard_text, robot_file, camera, subpixel).forNear();
}

}  // namespace climbsim::scene
