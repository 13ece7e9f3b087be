/// climbsim-scene: the scene service (docs/design.md#models, docs/scene-files.md#scene-xml). Reads
/// drive/RobotState (pose of the robot frame R in the wall frame W), places the robot's parts in
/// the scene and writes scene/DepthImage (height of the wall under the robot) and scene/LaserScan
/// every due step. Different rates for the two: run two instances, each with --outputs and its own
/// --period. Whenever a recorder records it, it also puts a reduced depth image (scene/DepthGrid,
/// 64 x 64 block means) into its record batches every 0.1 s of simulated time: the wall of replays
/// and of the live viewer, without a delivery of its own.
/// With --scenario the scene file comes from the scenario ("$BUILD/" = this build's directory).
/// With --tile I/N it renders only the part of the depth image that sealing shard I of N needs
/// (run it on the shard's host: only poses cross the network).

#include <CLI/CLI.hpp>
#include <optional>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/height_grid.hpp"
#include "climbsim/topic_names.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/names.hpp"
#include "climbsim/scenario.hpp"
#include "node/scene_node.hpp"
#include "node/scene_translate.hpp"
#include "shard_tile.hpp"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"

#ifndef CLIMBSIM_DEFAULT_SCENE_FILE
#error "CLIMBSIM_DEFAULT_SCENE_FILE must name the default scene (generated at build time)"
#endif
#ifndef CLIMBSIM_BUILD_DIR
#error "CLIMBSIM_BUILD_DIR must name the build directory (a scenario's $BUILD/)"
#endif

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-scene: depth camera and laser scanner on the scene XML"};
  ParticipantOptions options;
  scene::SceneNodeOptions node_options;
  std::string scene_file = CLIMBSIM_DEFAULT_SCENE_FILE;
  std::string outputs_list = "depth,laser";
  std::string tile_text;
  std::string backend = "rasterizer";
  int depth_size_px = 0;
  double depth_width_m = 0.0, near_m = 0.0, far_m = 0.0;
  std::string scenario_file;
  std::vector<std::string> overrides;
  options.addOptions(app);
  auto* scenario_opt = app.add_option("--scenario", scenario_file,
                                      "scenario file (deploy/scenarios/*.yaml): the scene comes from it; excludes --scene");
  app.add_option("--set", overrides, "override a scenario key, e.g. --set scene=FILE (repeatable)")->needs(scenario_opt);
  app.add_option("--scene", scene_file, "scene XML (docs/scene-files.md#scene-xml)")
      ->excludes(scenario_opt);
  app.add_option("--pose-element", node_options.pose_element, "3d Pose element that RobotState sets");
  app.add_option("--camera", node_options.camera,
                 "scene camera giving the depth camera's mount and defaults; \"\": the robot frame, defaults");
  app.add_option("--laser", node_options.laser, "scene distance_sensor of the laser scan");
  app.add_option("--outputs", outputs_list, "topics to write, comma-separated from depth,laser");
  app.add_option("--depth-size-px", depth_size_px, "depth image side [px] (default: the scene camera's, else 256)");
  app.add_option("--depth-width-m", depth_width_m, "depth image side on the wall [m] (default: camera size, else 0.8)");
  app.add_option("--near", near_m, "highest height seen above the sealing plane [m] (default 0.05)");
  app.add_option("--far", far_m, "lowest height reported [m] (default -0.05)");
  app.add_flag("--quantise-8bit", node_options.quantise_8bit, "quantise heights to 256 levels over [far, near]");
  app.add_option("--depth-backend", backend, "rasterizer or embree");
  app.add_option("--tile", tile_text,
                 "I/N: render only the part of the depth image sealing shard I of N needs (run one per shard, "
                 "next to the shards; rasterizer only)");
  return guardedMain(app, argc, argv, "scene", [&]() -> int {
    initLogging(options.name);
    std::string robot_file;
    if (!scenario_file.empty()) {
      const Scenario scenario = loadScenario(scenario_file, overrides);
      scene_file = scenario.scenePath(CLIMBSIM_BUILD_DIR);
      robot_file = scenario.robotPath();
      if (scenario.depth_camera.size_px > 0) node_options.depth_size_px = scenario.depth_camera.size_px;
    }
    if (app.count("--depth-size-px")) node_options.depth_size_px = depth_size_px;
    if (app.count("--depth-width-m")) node_options.depth_width_m = depth_width_m;
    if (app.count("--near")) node_options.near_m = near_m;
    if (app.count("--far")) node_options.far_m = far_m;
    if (backend == "embree") {
      node_options.backend = scene::DepthBackend::kEmbree;
    } else if (backend != "rasterizer") {
      throw ConfigError("--depth-backend = '" + backend + "': expected rasterizer or embree");
    }
    bool write_depth = false, write_laser = false;
    for (const auto& output : parseNameList("--outputs", outputs_list)) {
      if (output == "depth") {
        write_depth = true;
      } else if (output == "laser") {
        write_laser = true;
      } else {
        throw ConfigError("--outputs: unknown output '" + output + "' (expected depth, laser)");
      }
    }
    if (!write_laser) node_options.laser.clear();

    scene::Scene scene_graph = scene::loadScene(scene_file);
    if (!tile_text.empty()) {
      if (write_laser) throw ConfigError("--tile = '" + tile_text + "': renders depth only (--outputs depth)");
      if (robot_file.empty()) throw ConfigError("--tile = '" + tile_text + "': needs --scenario (the robot's sealing)");
      // Each frame's tile for the frame's height bound (from the scene's geometry): the pixels
      // the shard can read under it; the near plane's tile (all it can ever read) until then.
      const auto tiles = std::make_shared<scene::ShardTiles>(tile_text, robot_file,
                                                      scene::depthCameraParams(scene_graph, node_options));
      node_options.depth_tile = tiles->forNear();
      node_options.depth_tile_for_bound = [tiles](double height_bound_m) { return tiles->forBound(height_bound_m); };
    }
    scene::SceneNode node(std::move(scene_graph), node_options);
    spdlog::info("scene: {} with {} static triangles, {} px x {} px at {} mm, robot parts: {}", scene_file,
                 node.staticTriangleCount(), node.camera().width_px, node.camera().height_px,
                 node.camera().pixel_size_m * 1e3, node.robotPartIds().size());

    LockstepParticipant participant(options);
    auto& robot_state = participant.input<RobotStatePubSubType>(scene::topic::kRobotState);
    auto* depth = write_depth ? &participant.output<DepthImagePubSubType>(scene::topic::kDepthImage) : nullptr;
    auto* laser = write_laser ? &participant.output<LaserScanPubSubType>(scene::topic::kLaserScan) : nullptr;
    // Only a renderer of the whole image can reduce it (a tile renderer has a part of it).
    auto* grid = write_depth && tile_text.empty() ? &participant.output<DepthGridPubSubType>(topic::kDepthGrid) : nullptr;
    // The grid goes at the first due step at or after each multiple of kGridInterval_ns:
    // a function of the step alone, so the same run records the same grids.
    constexpr std::int64_t kGridInterval_ns = 100'000'000;
    constexpr int kGridCells = 64;
    std::int64_t next_grid_ns = 0;

    const int code = participant.run([&](const StepContext& ctx) {
      node.applyRobotStates(robot_state.get(ctx));
      if (depth) {
        std::optional<StatsTimer> render("depth_render_s");
        auto image = node.renderDepth();
        render.reset();
        StatsCpuTimer publish("depth_publish_cpu_s");
        // The reduced grid first (it reads the pixels), then the pixels move into the sample
        // (no copy of the image); written in the same order as ever: image, then grid.
        std::optional<climbsim::DepthGrid> reduced;
        if (grid && ctx.t_ns >= next_grid_ns && participant.isRecorded(topic::kDepthGrid)) {
          next_grid_ns = (ctx.t_ns / kGridInterval_ns + 1) * kGridInterval_ns;
          try {
            reduced = scene::depthGridToIdl(downsampleHeights(
                image.height_m, static_cast<std::uint32_t>(image.width_px), static_cast<std::uint32_t>(image.height_px),
                image.pixel_size_m, blockFor(static_cast<std::uint32_t>(image.width_px), kGridCells)));
          } catch (const std::invalid_argument& e) {  // e.g. a camera that is not square: no grids
            spdlog::warn("scene: no depth grid for replays: {}", e.what());
            grid = nullptr;
          }
        }
        auto sample = scene::depthImageToIdl(std::move(image));
        depth->write(ctx, sample);
        if (reduced) grid->write(ctx, *reduced);
      }
      if (laser) {
        auto sample = scene::laserScanToIdl(node.scanLaser(), node.scannerPoseInWall());
        laser->write(ctx, sample);
      }
    });
    logDroppedSamples(node.droppedRobotStates(), "RobotState samples");
    return code;
  });
}
