#include "shard_tile.hpp"

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "sealing_model.hpp"
#include "sealing_node.hpp"

namespace climbsim::scene {

PixelTile shardTile(const std::string& shard_text, const std::string& robot_file, const DepthCameraParams& camera) {
  sealing::ShardSpec spec;
  try {
    spec = sealing::ShardSpec::parse(shard_text);
  } catch (const ConfigError& e) {
    throw ConfigError("--tile" + std::string(e.what()).substr(std::string("--shard").size()));
  }
  const RobotDescription robot = loadRobotDescription(robot_file);
  const RobotGeometry geometry = computeGeometry(robot);
  const sealing::PixelGrid grid{camera.width_px, camera.height_px, camera.pixel_size_m};
  const sealing::SealingModel model(sealing::sealingParamsFromRobot(robot, geometry), geometry, grid, robot_file);
  // As the shard does (SealingNode::neededBox): near plus the 1 µm the shard admits above it.
  const double upper_bound_m = camera.near_m + 1e-6;
  const std::vector<std::size_t> segments = spec.segments(model.masks());
  const sealing::PixelBox box = model.neededBox(segments, upper_bound_m);
  // The pixels of the box the shard can ever read (the static region neededBox bounds): the
  // only ones rendered, and the only ones sent (the mask's runs).
  const std::vector<std::uint32_t> pixels = model.neededPixels(segments, upper_bound_m);
  PixelTile tile{box.row0, box.col0, box.rows, box.cols, nullptr};
  tile.mask = std::make_shared<const PixelMask>(camera.width_px, camera.height_px, pixels);
  return tile;
}

}  // namespace climbsim::scene
