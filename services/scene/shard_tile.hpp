#pragma once
/// @file
/// The tile of the depth image that `climbsim-scene --tile I/N` renders: the pixels sealing
/// shard I of N can ever read (SealingModel::neededBox with the camera's near plane), so that a
/// renderer next to each shard sends it only what it needs (issue 14).

#include <string>

#include "render/depth_camera.hpp"

namespace climbsim::scene {

/// The tile for `shard_text` ("I/N", as climbsim-sealing's --shard) of the robot in
/// `robot_file` under `camera`. ConfigError naming --tile for a malformed I/N or a shard
/// without segments.
PixelTile shardTile(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera);

}  // namespace climbsim::scene
