#include "hires_tiles.hpp"

#include <time.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "render_scene.hpp"
#include "scene_node.hpp"
#include "scene_translate.hpp"
#include "shard_tile.hpp"

namespace climbsim::bench {

namespace {

using json = nlohmann::json;
using scene::DepthCameraParams;
using scene::PixelTile;
using scene::RasterCounters;
using scene::Pose;

constexpr double kPi = 3.14159265358979323846;

// CPU time of this thread [s].
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// One layout of `--hires`: a tile (or the whole image) rendered over every pose.
struct TileCost {
  std::string name;
  PixelTile tile;
  double cpu_ms = 0.0;  ///< per frame, this thread
  std::uint64_t fnv = 14695981039346656037ull;  ///< FNV-1a of every frame's pixel bits (compares builds)
  RasterCounters work{};  ///< per frame (mean)
};

}  // namespace

int hiresTiles(const std::string& scene_file, const std::string& robot_file, int frames, const std::string& out_path,
               const std::string& only_layout) {
  scene::SceneNodeOptions options;
  options.depth_size_px = 1024;
  options.depth_width_m = 0.8;
  scene::SceneNode node(scene::loadScene(scene_file), options);
  // crack-descent-hires: from (1.0, 1.2) at yaw -90° down the wall at 0.05 m/s, a depth frame
  // every 10 ms (0.5 mm); the camera poses as the scene service places them.
  std::vector<Pose> camera_poses;
  for (int k = 0; k < frames; ++k) {
    Pose T = Pose::Identity();
    T.linear() = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(1.0, 1.2 - 0.0005 * k, 0.0);
    auto state = scene::robotStateToIdl(T);
    state.source("drive");
    node.applyRobotStates({state});
    node.renderDepth();
    camera_poses.push_back(node.cameraPose());
  }
  const DepthCameraParams whole_camera = node.camera();
  scene::RenderScene sensors(node.scene().staticMesh());
  const std::vector<std::uint32_t>& robot = node.robotPartIds();

  std::vector<TileCost> layouts{{"whole", PixelTile{}, 0.0, {}}};
  for (const int n : {2, 4}) {
    for (int i = 0; i < n; ++i) {
      const std::string shard = std::to_string(i) + "/" + std::to_string(n);
      const PixelTile tile = scene::shardTile(shard, robot_file, whole_camera);
      layouts.push_back({shard, tile, 0.0, {}});
      PixelTile box = tile;  // the box alone, every pixel of it rendered
      box.mask.reset();
      layouts.push_back({shard + "-box", box, 0.0, {}});
    }
  }
  layouts.push_back({"top-half", PixelTile{0, 0, 512, 1024}, 0.0, {}});
  layouts.push_back({"bottom-half", PixelTile{512, 0, 512, 1024}, 0.0, {}});
  scene::DepthImage image;
  for (TileCost& layout : layouts) {
    if (!only_layout.empty() && layout.name != only_layout && layout.name != "whole") continue;
    DepthCameraParams camera = whole_camera;
    camera.tile = layout.tile;
    sensors.renderDepth(camera_poses.front(), camera, robot, image);  // warm-up
    const double cpu0 = threadCpuSeconds();
    for (const Pose& T : camera_poses) {
      sensors.renderDepth(T, camera, robot, image);
      layout.work += sensors.lastDepthCounters();
    }
    layout.cpu_ms = 1e3 * (threadCpuSeconds() - cpu0) / frames;
    for (const Pose& T : camera_poses) {  // not timed
      sensors.renderDepth(T, camera, robot, image);
      const auto* bytes = reinterpret_cast<const unsigned char*>(image.height_m.data());
      for (std::size_t i = 0; i < image.height_m.size() * sizeof(float); ++i) layout.fnv = (layout.fnv ^ bytes[i]) * 1099511628211ull;
    }
    layout.work.leaves /= frames;
    layout.work.triangles /= frames;
  }
  const TileCost& whole = layouts.front();
  std::printf("bench: scene: hires whole cpu_ms=%.2f leaves=%llu triangles=%llu (%d x %d px, %d frames, %zu static "
              "triangles, raster_kernel=%s) pixels_fnv=%016llx\n",
              whole.cpu_ms, static_cast<unsigned long long>(whole.work.leaves),
              static_cast<unsigned long long>(whole.work.triangles), whole_camera.width_px, whole_camera.height_px, frames,
              sensors.staticTriangleCount(), scene::rasterKernelName(), static_cast<unsigned long long>(whole.fnv));
  json report{{"name", "scene-hires"}, {"frames", frames}, {"width_px", whole_camera.width_px}};
  const double pixels = static_cast<double>(whole_camera.width_px) * whole_camera.height_px;
  for (const TileCost& layout : layouts) {
    if (!only_layout.empty() && layout.name != only_layout && layout.name != "whole") continue;
    const double tile_pixels = layout.tile.mask    ? static_cast<double>(layout.tile.mask->count())
                               : layout.tile.whole() ? pixels
                                                     : static_cast<double>(layout.tile.rows) * layout.tile.cols;
    const double cpu_share = layout.cpu_ms / whole.cpu_ms;
    const double triangle_share = static_cast<double>(layout.work.triangles) / whole.work.triangles;
    if (&layout != &whole) {
      std::printf("bench: scene: hires tile=%s rows=%d+%d cols=%d+%d pixel_share=%.3f cpu_share=%.3f (cpu_ms %.2f / "
                  "%.2f whole) triangle_share=%.3f leaf_share=%.3f\n",
                  layout.name.c_str(), layout.tile.row0, layout.tile.rows, layout.tile.col0, layout.tile.cols,
                  tile_pixels / pixels, cpu_share, layout.cpu_ms, whole.cpu_ms, triangle_share,
                  static_cast<double>(layout.work.leaves) / whole.work.leaves);
    }
    report["layouts"].push_back({{"name", layout.name},
                                 {"tile", {layout.tile.row0, layout.tile.col0, layout.tile.rows, layout.tile.cols}},
                                 {"cpu_ms", layout.cpu_ms},
                                 {"pixel_share", tile_pixels / pixels},
                                 {"cpu_share", cpu_share},
                                 {"triangles", layout.work.triangles},
                                 {"leaves", layout.work.leaves}});
  }
  if (!out_path.empty()) {
    std::ofstream f(out_path);
    if (!f) throw ConfigError("--out = '" + out_path + "': cannot write it");
    f << report.dump(2) << "\n";
  }
  return kExitOk;
}

}  // namespace climbsim::bench
