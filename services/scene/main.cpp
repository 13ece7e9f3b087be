/// climbsim-scene: the scene service (docs/design.md#models, docs/scene-files.md#scene-xml). Reads
/// drive/RobotState (pose of the robot frame R in the wall frame W), places the robot's parts in
/// the scene and writes scene/DepthImage (height of the wall under the robot) and scene/LaserScan
/// every due step. Different rates for the two: run two instances, each with --outputs and its own
/// --period. Whenever a recorder records it, it also puts a reduced depth image (scene/DepthGrid,
/// 64 x 64 block means) into its record batches every 0.1 s of simulated time: the wall of replays
/// and of the live viewer, without a delivery of its own (node/scene_participant.hpp).
/// With --scenario the scene file comes from the scenario ("$BUILD/" = this build's directory).
/// With --tile I/N it renders only the part of the depth image that sealing shard I of N needs
/// (run it on the shard's host: only poses cross the network). Without --tile, with a scenario,
/// it renders every frame at the pixels the whole sealing reads and whole only the frames another
/// reader reads whole (docs/design.md#what-the-scene-renders).

#include <spdlog/spdlog.h>

#include <memory>

#include "climbsim/errors.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/service_command_line.hpp"
#include "configure.hpp"
#include "node/scene_participant.hpp"
#include "shard_tile.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  ServiceCommandLine cli("climbsim-scene: depth camera and laser scanner on the scene XML",
                         "scenario file (deploy/scenarios/*.yaml): the scene comes from it; excludes --scene",
                         "scene=FILE");
  scene::SceneOverrides o;
  std::string tile_text;
  CLI::App& app = cli.app;
  app.add_option("--scene", o.scene_file, "scene XML (docs/scene-files.md#scene-xml)")->excludes(cli.scenario_option);
  app.add_option("--pose-element", o.pose_element, "3d Pose element that RobotState sets");
  app.add_option("--camera", o.camera,
                 "scene camera giving the depth camera's mount and defaults; \"\": the robot frame, defaults");
  app.add_option("--laser", o.laser, "scene distance_sensor of the laser scan");
  app.add_option("--outputs", o.outputs, "topics to write, comma-separated from depth,laser");
  app.add_option("--depth-size-px", o.depth_size_px, "depth image side [px] (default: the scene camera's, else 256)");
  app.add_option("--depth-width-m", o.depth_width_m,
                 "depth image side on the wall [m] (default: the scene camera's size, else the robot's view)");
  cli.addRobotOption("robot description without --scenario: the depth image's default side (deploy/robots/*.yaml)");
  app.add_option("--near", o.near_m, "highest height seen above the sealing plane [m] (default 0.05)");
  app.add_option("--far", o.far_m, "lowest height reported [m] (default -0.05)");
  app.add_flag("--quantise-8bit", o.quantise_8bit, "quantise heights to 256 levels over [far, near]");
  app.add_option("--depth-backend", o.backend, "rasterizer or embree");
  app.add_option("--tile", tile_text,
                 "I/N: render only the part of the depth image sealing shard I of N needs (run one per shard, "
                 "next to the shards; rasterizer only)");
  return cli.run(argc, argv, "scene", [&]() -> int {
    initLogging(cli.participant.name);
    scene::SceneSetup setup = scene::configureScene(cli.load(), o, thisBuildDir());
    scene::Scene scene_graph = scene::loadRunScene(setup);
    if (!tile_text.empty()) {
      if (setup.write_laser) throw ConfigError("--tile = '" + tile_text + "': renders depth only (--outputs depth)");
      if (setup.robot_file.empty()) throw ConfigError("--tile = '" + tile_text + "': needs --scenario (the robot's sealing)");
      // Each frame's tile for the frame's height bound (from the scene's geometry): the pixels
      // the shard can read under it; the near plane's tile (all it can ever read) until then.
      const auto tiles = std::make_shared<scene::ShardTiles>(
          tile_text, setup.robot_file, scene::depthCameraParams(scene_graph, setup.params), setup.subpixel);
      setup.params.depth_tile = tiles->forNear();
      setup.params.depth_tile_for_bound = [tiles](double height_bound_m) { return tiles->forBound(height_bound_m); };
    }
    // A --tile renders its shard's tiles; else the sealing's pixels but for the frames read whole.
    const scene::DepthFrameChoice frames = tile_text.empty() ? setup.frames : scene::DepthFrameChoice{};
    scene::SceneNode node(std::move(scene_graph), setup.params, frames);
    spdlog::info("scene: {} with {} static triangles, {} px x {} px at {} mm, robot parts: {}", setup.scene_file,
                 node.staticTriangleCount(), node.camera().width_px, node.camera().height_px,
                 node.camera().pixel_size_m * 1e3, node.robotPartIds().size());
    return scene::runSceneParticipant(cli.participant, setup, !tile_text.empty(), node);
  });
}
