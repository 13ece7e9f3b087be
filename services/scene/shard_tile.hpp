#pragma once
/// @file
/// The tile of the depth image that `climbsim-scene --tile I/N` renders: the box of the pixels
/// sealing shard I of N can ever read (SealingModel::neededBox with the camera's near plane),
/// so that a renderer next to each shard sends it only what it needs (issue 14), and as its
/// mask those pixels themselves (the region's static part): only they are rendered, the rest of
/// the box holds far.

#include <string>

#include "render/depth_camera.hpp"

namespace climbsim::scene {

/// The tile (with its mask) for `shard_text` ("I/N", as climbsim-sealing's --shard) of the robot in
/// `robot_file` under `camera`. ConfigError naming --tile for a malformed I/N or a shard
/// without segments.
PixelTile shardTile(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera);

}  // namespace climbsim::scene
