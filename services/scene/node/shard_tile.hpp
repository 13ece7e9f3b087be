#pragma once
/// @file
/// The tile of the depth image that `climbsim-scene --tile I/N` renders: the box of the pixels
/// sealing shard I of N can read (SealingModel::neededBox), so that a renderer next to each
/// shard sends it only what it needs (sharded sealing), and as its mask those pixels themselves
/// (the region's static part): only they are rendered and sent. How far the region reaches along
/// the strips grows with the highest height the image can hold: with the camera's near plane as the
/// bound (shardTile) it is every pixel the shard can ever need; with each frame's bound from the
/// scene's geometry (ShardTiles) far fewer.

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "depth_camera.hpp"

namespace climbsim::sealing {
class ShardPixels;
class StripMasks;
}

namespace climbsim::scene {

/// The tiles of one shard, one per height bound that gives another set of pixels (whole bands
/// of the shard's region), built on first use. Thread-safe.
class ShardTiles {
 public:
  /// For `shard_text` ("I/N", as climbsim-sealing's --shard) of the robot in `robot_file` under
  /// `camera`, whose strips are sub-pixel shares when `subpixel` (the scenario's
  /// depth_camera.subpixel, as the shard's), else whole pixels by their centres. ConfigError
  /// naming --tile for a malformed I/N or a shard without segments.
  ShardTiles(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera,
             bool subpixel = false);
  ~ShardTiles();

  /// The tile holding every pixel the shard reads of an image none of whose heights exceeds
  /// `height_bound_m` [m] (as the shard bounds it: plus the 1 µm it admits).
  PixelTile forBound(double height_bound_m);
  /// The tile for the camera's near plane: every pixel the shard can ever read.
  PixelTile forNear() { return forBound(near_m_); }

 private:
  std::unique_ptr<const sealing::StripMasks> masks_;
  std::unique_ptr<const sealing::ShardPixels> pixels_;  ///< of masks_
  std::vector<std::size_t> segments_;
  int width_px_ = 0, height_px_ = 0;
  double near_m_ = 0.0;
  std::mutex mutex_;
  std::map<std::size_t, PixelTile> by_count_;  ///< by SealingModel::neededCount
};

/// The tiles of the whole sealing of the robot in `robot_file` under `camera` (ShardTiles of
/// shard 0/1) as SceneParams::depth_tile_for_bound: each frame's pixels the sealing can read
/// under the frame's height bound (docs/design.md#what-the-scene-renders).
std::function<PixelTile(double)> wholeSealingTiles(const std::string& robot_file, const DepthCameraParams& camera,
                                                   bool subpixel);

/// ShardTiles(shard_text, robot_file, camera, subpixel).forNear().
PixelTile shardTile(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera,
                    bool subpixel = false);

}  // namespace climbsim::scene
