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
  const sealing::PixelBox box = model.neededBox(spec.segments(model.masks()), camera.near_m + 1e-6);
  return PixelTile{box.row0, box.col0, box.rows, box.cols};
}

}  // namespace climbsim::scene
