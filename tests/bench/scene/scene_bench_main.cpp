/// climbsim-bench-scene: the depth camera and the laser scanner on a pylon-sized wall
/// on one core.
///
/// Wall (built in code, seeded): a square pylon 2 m wide and `levels` 2 m blocks high, so
/// 4 * levels faces of 2 m x 2 m (12 by default), each a height field at `spacing` (4 mm)
/// with rough concrete (about 1 mm RMS, ~2 cm correlation, plus 0.2 mm grain) and a crack
/// (6 mm wide, 8 mm deep) across it; one part per face. Default: 6.0 million triangles.
///
/// Camera: 256 x 256 px over 0.80 m (the default robot's camera) in the robot frame, which drives over
/// the faces 2 mm per frame (0.1 m/s at 50 Hz) with slowly turning yaw, hopping to another
/// face every 200 frames; a second run uses independent random poses (cold caches).
///
///   depth_fps_raster, depth_fps_embree   256x256 frames per CPU second of the rendering thread
///                                        (the machine may be shared), same pose sequence
///   embree_vs_raster                     depth_fps_embree / depth_fps_raster (< 1: Embree slower)
///   laser_scans_per_s                    682-beam, 4 m scans from 0.35 m above the robot,
///                                        pitched 20° towards the wall (scene XML offset)
///   max_backend_diff_m                   largest |raster - embree| over the compared frames
///
///   bench: scene: triangles=.. depth_fps_raster=.. depth_fps_embree=.. embree_vs_raster=..
///          laser_scans_per_s=.. target_fps=500 met=yes|no
///
/// Options: --out FILE (JSON), --frames N (default 1000), --spacing-mm S (default 4),
/// --levels L (default 3), --seed N (default 1), --raster-kernel auto|generic|avx2|avx512
/// (default auto: the widest the CPU runs).
///
/// `--hires` measures instead what a tile renderer of sharded sealing costs: the default pylon
/// scene under crack-descent-hires's camera (1024 x 1024 px over 0.8 m) along its descent, the
/// whole image against the tiles of `climbsim-scene --tile I/N` (N = 2, 4; pixel_share: the pixels
/// rendered, the shard's mask; "-box": every pixel of the tile's box), and two plain halves, each
/// in CPU ms per frame of this thread and in work counted by the rasteriser (leaves,
/// triangles), each share printed beside the whole image's figure it divides:
///
///   bench: scene: hires whole cpu_ms=.. leaves=.. triangles=..
///   bench: scene: hires tile=I/N rows=.. cols=.. pixel_share=.. cpu_share=.. triangle_share=..
///
/// `--crack-descent` measures instead the default run's depth frames: crack-descent's camera
/// (256 x 256 px over 0.8 m) on the default pylon along its poses (held 2 s, then down at
/// 5 cm/s, 50 frames/s), CPU ms per frame of this thread, by the renderer and by its reference
/// path (RenderOptions::reference_raster) in the same run, centre rays only and with the
/// sub-pixel option's area-weighted edge pixels; differing_frames counts frames whose pixels
/// or support heights differ in any bit between the two (exit code 1 if any). render_ms is what the default run
/// renders per frame (SceneNode with the scenario's DepthFrameChoice: the whole sealing's
/// pixels, whole frames every 0.1 s and at the sealing pictures, averaged by their share;
/// docs/design.md#what-the-scene-renders), its pixels checked against the whole image's:
///
///   bench: scene: crack-descent render_ms=.. target_ms=0.25 met=.. render_ms_whole=.. render_ms_masked=..
///          whole_frames=W/N masked_pixels=../.. differing_frames=0/N
///   bench: scene: crack-descent render_ms_whole=.. reference_render_ms=.. speedup=..
///          differing_frames=0/N pixels_fnv=..
///   bench: scene: crack-descent render_ms_subpixel=.. reference_render_ms_subpixel=.. speedup=..
///          over_centre_rays=.. differing_frames=0/N pixels_fnv=.. supports_fnv=..
///
/// `--crack-descent --subpixel-only`: only the renderer's frames with the sub-pixel option, for
/// a profiler (`perf record`), one line, nothing compared; `--masked-only`: likewise the
/// renderer alone on the default run's masked frames (the sealing's pixels).

#include <CLI/CLI.hpp>
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "depth_rasterizer.hpp"
#include "render_scene.hpp"
#include "climbsim/wall/scene.hpp"
#include "crack_descent_frames.hpp"
#include "hires_tiles.hpp"

using nlohmann::json;
using namespace climbsim;
using namespace climbsim::scene;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFace_m = 2.0;
constexpr double kTargetFps = 500.0;

// Uniform in [-1, 1) from 53 bits of the generator: the same on every platform.
double uniformPm1(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-52 - 1.0; }

// Smooth random field: value noise on a lattice of `cell_m`, smoothstep-interpolated.
struct ValueNoise {
  int n = 0;
  double cell_m = 0.0;
  std::vector<double> values;
  ValueNoise(std::mt19937_64& rng, double extent_m, double cell) : n(static_cast<int>(extent_m / cell) + 2), cell_m(cell) {
    values.resize(static_cast<std::size_t>(n) * n);
    for (double& v : values) v = uniformPm1(rng);
  }
  double operator()(double x, double y) const {
    const double fx = x / cell_m, fy = y / cell_m;
    const int i = std::clamp(static_cast<int>(fx), 0, n - 2), j = std::clamp(static_cast<int>(fy), 0, n - 2);
    auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
    const double u = smooth(fx - i), v = smooth(fy - j);
    auto at = [&](int a, int b) { return values[static_cast<std::size_t>(b) * n + a]; };
    return (1 - v) * ((1 - u) * at(i, j) + u * at(i + 1, j)) + v * ((1 - u) * at(i, j + 1) + u * at(i + 1, j + 1));
  }
};

Pose makePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Pose T = Pose::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

// Face frame F: origin at the face centre, x_F horizontal along the face, y_F up (world z),
// z_F the outward normal. Side 0..3: normals +x, +y, -x, -y.
Pose faceFrame(int side, int level) {
  const double a = side * kPi / 2.0;
  const Eigen::Vector3d normal(std::cos(a), std::sin(a), 0.0);
  const Eigen::Vector3d up(0, 0, 1);
  Eigen::Matrix3d R;
  R.col(0) = up.cross(normal);
  R.col(1) = up;
  R.col(2) = normal;
  return makePose(R, normal * (kFace_m / 2) + up * (kFace_m * (level + 0.5)));
}

TriangleMesh buildPylon(int levels, double spacing_m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int cells = static_cast<int>(std::lround(kFace_m / spacing_m));
  const int side_vertices = cells + 1;
  TriangleMesh mesh;
  const std::size_t faces = static_cast<std::size_t>(4 * levels);
  mesh.vertices_m.reserve(faces * side_vertices * side_vertices);
  mesh.triangles.reserve(faces * 2 * cells * cells);
  mesh.part_ids.reserve(faces * 2 * cells * cells);
  for (int level = 0; level < levels; ++level) {
    for (int side = 0; side < 4; ++side) {
      const Pose T_W_F = faceFrame(side, level);
      const ValueNoise coarse(rng, kFace_m, 0.02);
      const ValueNoise broad(rng, kFace_m, 0.25);
      // A straight crack through a random point at a random angle.
      const double crack_angle = kPi * (0.5 + 0.5 * uniformPm1(rng));
      const Eigen::Vector2d crack_dir(std::cos(crack_angle), std::sin(crack_angle));
      const Eigen::Vector2d crack_point(0.5 * uniformPm1(rng), 0.5 * uniformPm1(rng));
      const auto first = static_cast<std::uint32_t>(mesh.vertices_m.size());
      for (int j = 0; j < side_vertices; ++j) {
        for (int i = 0; i < side_vertices; ++i) {
          const double x = -kFace_m / 2 + i * spacing_m, y = -kFace_m / 2 + j * spacing_m;
          double h = 0.0012 * coarse(x + 1.0, y + 1.0) + 0.002 * broad(x + 1.0, y + 1.0) + 0.0002 * uniformPm1(rng);
          const Eigen::Vector2d rel = Eigen::Vector2d(x, y) - crack_point;
          const double across = std::abs(rel.x() * crack_dir.y() - rel.y() * crack_dir.x());
          if (across < 0.003) h -= 0.008;
          mesh.vertices_m.push_back((T_W_F * Eigen::Vector3d(x, y, h)).cast<float>());
        }
      }
      const auto part = static_cast<std::uint32_t>(level * 4 + side);
      for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
          const std::uint32_t v00 = first + j * side_vertices + i, v10 = v00 + 1, v01 = v00 + side_vertices,
                              v11 = v01 + 1;
          mesh.triangles.push_back({v00, v10, v11});
          mesh.triangles.push_back({v00, v11, v01});
          mesh.part_ids.push_back(part);
          mesh.part_ids.push_back(part);
        }
      }
    }
  }
  return mesh;
}

// Robot pose R on face (side, level) at (x, y) in F, yaw about z_F, tiny roll/pitch as on a
// rough wall, sealing plane a little above the mean surface.
Pose robotPose(int side, int level, double x, double y, double yaw, double roll, double pitch, double lift) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return faceFrame(side, level) * makePose(R, Eigen::Vector3d(x, y, lift));
}

std::vector<Pose> trajectoryPoses(int frames, int levels, std::uint64_t seed) {
  std::mt19937_64 rng(seed + 101);
  std::vector<Pose> poses;
  const double margin = 0.45, half = kFace_m / 2 - margin;
  int side = 0, level = 0;
  double x = 0, y = 0, heading = 0, yaw = 0;
  for (int k = 0; k < frames; ++k) {
    if (k % 200 == 0) {
      side = static_cast<int>(rng() % 4);
      level = static_cast<int>(rng() % levels);
      x = half * uniformPm1(rng);
      y = half * uniformPm1(rng);
      heading = kPi * uniformPm1(rng);
      yaw = kPi * uniformPm1(rng);
    }
    heading += 0.02 * uniformPm1(rng);
    yaw += 0.01;
    x += 0.002 * std::cos(heading);
    y += 0.002 * std::sin(heading);
    if (std::abs(x) > half) heading = kPi - heading, x = std::clamp(x, -half, half);
    if (std::abs(y) > half) heading = -heading, y = std::clamp(y, -half, half);
    poses.push_back(robotPose(side, level, x, y, yaw, 0.005 * uniformPm1(rng), 0.005 * uniformPm1(rng),
                              0.001 + 0.001 * uniformPm1(rng)));
  }
  return poses;
}

std::vector<Pose> randomPoses(int frames, int levels, std::uint64_t seed) {
  std::mt19937_64 rng(seed + 202);
  std::vector<Pose> poses;
  for (int k = 0; k < frames; ++k) {
    const int side = static_cast<int>(rng() % 4), level = static_cast<int>(rng() % levels);
    poses.push_back(robotPose(side, level, 0.55 * uniformPm1(rng), 0.55 * uniformPm1(rng), kPi * uniformPm1(rng),
                              0.005 * uniformPm1(rng), 0.005 * uniformPm1(rng), 0.001 + 0.001 * uniformPm1(rng)));
  }
  return poses;
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// CPU time of this thread [s]: the machine may be shared, and "one core" is what counts.
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct DepthRun {
  double fps = 0.0;       // per CPU second of this thread
  double wall_fps = 0.0;  // per wall second (lower when the machine is shared)
  std::vector<DepthImage> kept;  // every 50th frame, for comparing the backends
  double mean_far_fraction = 0.0;
};

DepthRun timeDepth(RenderScene& scene, const std::vector<Pose>& poses, DepthBackend backend) {
  const DepthCameraParams camera;
  DepthImage image;
  DepthRun run;
  scene.renderDepth(poses.front(), camera, {}, backend, image);  // warm-up (and lazy index)
  std::size_t far_pixels = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = threadCpuSeconds();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    scene.renderDepth(poses[k], camera, {}, backend, image);
    if (k % 50 == 0) run.kept.push_back(image);
  }
  run.fps = static_cast<double>(poses.size()) / (threadCpuSeconds() - cpu0);
  run.wall_fps = static_cast<double>(poses.size()) / seconds(t0);
  for (const DepthImage& kept : run.kept) {
    far_pixels += std::count(kept.height_m.begin(), kept.height_m.end(), static_cast<float>(camera.far_m));
  }
  run.mean_far_fraction = static_cast<double>(far_pixels) / (run.kept.size() * image.height_m.size());
  return run;
}

/// The default pylon scene (generated at build time): its static triangles and robot poses
/// driving 2 mm per frame across its wall (the frame WALL, x in [-1.6, 3.6], y in [-5.6, 1.6]).
struct DefaultScene {
  TriangleMesh wall;
  std::vector<Pose> poses;
};

DefaultScene defaultScene(const std::string& path, int frames, std::uint64_t seed) {
  const climbsim::scene::Scene loaded = climbsim::scene::loadScene(path);
  DefaultScene d;
  d.wall = loaded.staticMesh();
  const Pose T_world_WALL = loaded.worldPose("WALL");
  std::mt19937_64 rng(seed + 303);
  double x = 1.0, y = -2.0, heading = 0.0, yaw = 0.0;
  for (int k = 0; k < frames; ++k) {
    if (k % 200 == 0) heading = kPi * uniformPm1(rng);
    heading += 0.02 * uniformPm1(rng);
    yaw += 0.01;
    x += 0.002 * std::cos(heading);
    y += 0.002 * std::sin(heading);
    if (x < -1.6 || x > 3.6) heading = kPi - heading, x = std::clamp(x, -1.6, 3.6);
    if (y < -5.6 || y > 1.6) heading = -heading, y = std::clamp(y, -5.6, 1.6);
    d.poses.push_back(T_world_WALL *
                      makePose(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(), Eigen::Vector3d(x, y, 0)));
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-scene: depth camera and laser scanner on a pylon wall, one core"};
  std::string out_path;
  int frames = 1000;
  double spacing_mm = 4.0;
  int levels = 3;
  std::uint64_t seed = 1;
  std::string kernel_name = "auto";
  app.add_option("--raster-kernel", kernel_name, "rasteriser kernel variant")
      ->check(CLI::IsMember({"auto", "generic", "avx2", "avx512"}));
  app.add_option("--out", out_path, "write the JSON report here");
  app.add_option("--frames", frames, "depth frames per backend and pose set")->check(CLI::PositiveNumber);
  app.add_option("--spacing-mm", spacing_mm, "wall grid spacing [mm]")->check(CLI::Range(1.0, 100.0));
  app.add_option("--levels", levels, "2 m blocks stacked (4 faces each)")->check(CLI::Range(1, 10));
  app.add_option("--seed", seed, "seed of the wall and the poses");
  std::string scene_file = CLIMBSIM_DEFAULT_SCENE_FILE;
  app.add_option("--scene", scene_file, "the default pylon scene, measured as well (\"\" to skip)");
  bool hires = false;
  app.add_flag("--hires", hires, "only the cost of tile renderers at 1024 px on the default pylon");
  std::string robot_file = CLIMBSIM_ROBOTS_DIR "/cromsci.yaml";
  app.add_option("--robot", robot_file, "--hires: the robot whose sealing shards the tiles serve");
  std::string hires_layout;
  app.add_option("--hires-layout", hires_layout, "--hires: only the whole image and this layout (e.g. 0/2, 0/2-box)");
  bool crack_descent = false;
  app.add_flag("--crack-descent", crack_descent,
               "only crack-descent's depth frames on the default pylon: the renderer against its reference path");
  std::string scenario_file = CLIMBSIM_SCENARIOS_DIR "/crack-descent.yaml";
  app.add_option("--scenario", scenario_file, "--crack-descent: the scenario whose camera and scene are rendered");
  bool subpixel_only = false;
  app.add_flag("--subpixel-only", subpixel_only,
               "--crack-descent: only the renderer's frames with 16 rays per edge pixel (for a profiler)");
  bool masked_only = false;
  app.add_flag("--masked-only", masked_only,
               "--crack-descent: only the renderer's frames on the default run's masks (for a profiler)");
  return guardedMain(app, argc, argv, "bench-scene", [&]() -> int {
    if (crack_descent) return climbsim::bench::crackDescentFrames(scenario_file, CLIMBSIM_BUILD_DIR, frames, out_path,
                                                                    subpixel_only, masked_only);
    if (hires) return climbsim::bench::hiresTiles(scene_file, robot_file, frames, out_path, hires_layout);
    auto t0 = std::chrono::steady_clock::now();
    const TriangleMesh wall = buildPylon(levels, spacing_mm * 1e-3, seed);
    const double generate_s = seconds(t0);

    t0 = std::chrono::steady_clock::now();
    RenderOptions options;
    options.depth_backend = DepthBackend::kEmbree;  // the rasteriser's index is timed separately
    options.embree_device_config = "threads=1";
    options.raster_kernel = kernel_name == "generic" ? RasterKernel::kGeneric
                            : kernel_name == "avx2"  ? RasterKernel::kAvx2
                            : kernel_name == "avx512" ? RasterKernel::kAvx512
                                                      : RasterKernel::kAuto;
    if (!rasterKernelSupported(options.raster_kernel)) {
      throw ConfigError("--raster-kernel = '" + kernel_name + "': this CPU does not run it");
    }
    const std::string kernel_used = kernel_name == "auto" ? rasterKernelName() : kernel_name;
    RenderScene scene(wall, options);
    const double embree_build_s = seconds(t0);
    t0 = std::chrono::steady_clock::now();
    DepthImage first_frame;
    scene.renderDepth(faceFrame(0, 0), DepthCameraParams{}, {}, DepthBackend::kRasterizer, first_frame);
    const double raster_build_s = seconds(t0);

    const std::vector<Pose> trajectory = trajectoryPoses(frames, levels, seed);
    const std::vector<Pose> random = randomPoses(frames, levels, seed);
    const DepthRun raster = timeDepth(scene, trajectory, DepthBackend::kRasterizer);
    const DepthRun embree = timeDepth(scene, trajectory, DepthBackend::kEmbree);
    const DepthRun raster_random = timeDepth(scene, random, DepthBackend::kRasterizer);
    const DepthRun embree_random = timeDepth(scene, random, DepthBackend::kEmbree);

    double max_diff = 0.0;
    std::size_t pixels_over_0_1mm = 0, compared = 0;
    for (const auto* pair : {&raster, &raster_random}) {
      const DepthRun& other = pair == &raster ? embree : embree_random;
      for (std::size_t f = 0; f < pair->kept.size(); ++f) {
        for (std::size_t i = 0; i < pair->kept[f].height_m.size(); ++i) {
          const double d = std::abs(double{pair->kept[f].height_m[i]} - other.kept[f].height_m[i]);
          max_diff = std::max(max_diff, d);
          pixels_over_0_1mm += d > 1e-4;
          ++compared;
        }
      }
    }

    // Laser: 0.35 m above the robot centre, pitched 20° (docs/scene-files.md#scene-xml
    // distance_sensor offset).
    const LaserParams laser;
    const Pose T_R_S = makePose(Eigen::AngleAxisd(20.0 * kPi / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                               Eigen::Vector3d(0, 0, 0.35));
    LaserScan scan;
    std::size_t hits = 0;
    const double cpu0 = threadCpuSeconds();
    for (const Pose& T_W_R : trajectory) {
      scene.scanLaser(T_W_R * T_R_S, laser, {}, scan);
      for (const float r : scan.ranges_m) hits += std::isfinite(r);
    }
    const double laser_scans_per_s = static_cast<double>(trajectory.size()) / (threadCpuSeconds() - cpu0);
    const double hit_fraction = static_cast<double>(hits) / (trajectory.size() * laser.beam_count);

    // The default pylon scene as generated at build time, rasteriser (the default backend).
    std::size_t default_triangles = 0;
    double default_fps = 0.0;
    if (!scene_file.empty()) {
      const DefaultScene pylon = defaultScene(scene_file, frames, seed);
      RenderOptions pylon_options = options;
      pylon_options.depth_backend = DepthBackend::kRasterizer;
      RenderScene pylon_scene(pylon.wall, pylon_options);
      default_triangles = pylon_scene.staticTriangleCount();
      default_fps = timeDepth(pylon_scene, pylon.poses, DepthBackend::kRasterizer).fps;
      std::printf("bench: scene: default_pylon_triangles=%zu default_pylon_fps_raster=%.0f target_fps=%.0f met=%s\n",
                  default_triangles, default_fps, kTargetFps, default_fps >= kTargetFps ? "yes" : "no");
    }

    struct rusage usage {};
    getrusage(RUSAGE_SELF, &usage);
    const double peak_rss_mb = usage.ru_maxrss / 1024.0;

    const double best_fps = std::max(raster.fps, embree.fps);
    const char* faster = raster.fps >= embree.fps ? "rasterizer" : "embree";
    const bool met = best_fps >= kTargetFps;
    std::printf("bench: scene: triangles=%zu depth_fps_raster=%.0f depth_fps_embree=%.0f embree_vs_raster=%.3f "
                "laser_scans_per_s=%.0f target_fps=%.0f met=%s\n",
                scene.staticTriangleCount(), raster.fps, embree.fps, embree.fps / raster.fps, laser_scans_per_s,
                kTargetFps, met ? "yes" : "no");
    std::printf("bench: scene: faster=%s random_pose_fps_raster=%.0f random_pose_fps_embree=%.0f "
                "wall_fps_raster=%.0f wall_fps_embree=%.0f max_backend_diff_m=%.3g pixels_over_0.1mm=%zu/%zu far_fraction=%.4f laser_hit_fraction=%.3f "
                "generate_s=%.2f embree_build_s=%.2f raster_index_build_s=%.2f peak_rss_mb=%.0f spacing_mm=%g faces=%d "
                "raster_kernel=%s\n",
                faster, raster_random.fps, embree_random.fps, raster.wall_fps, embree.wall_fps, max_diff, pixels_over_0_1mm, compared,
                raster.mean_far_fraction, hit_fraction, generate_s, embree_build_s, raster_build_s, peak_rss_mb,
                spacing_mm, 4 * levels, kernel_used.c_str());

    const json report = {
        {"name", "scene"},
        {"triangles", scene.staticTriangleCount()},
        {"faces", 4 * levels},
        {"spacing_mm", spacing_mm},
        {"frames", frames},
        {"image", {{"width_px", 256}, {"height_px", 256}, {"window_m", 0.8}}},
        {"depth_fps_raster", raster.fps},
        {"depth_fps_embree", embree.fps},
        {"embree_vs_raster", embree.fps / raster.fps},
        {"random_pose_fps_raster", raster_random.fps},
        {"random_pose_fps_embree", embree_random.fps},
        {"wall_fps_raster", raster.wall_fps},
        {"wall_fps_embree", embree.wall_fps},
        {"timing", "frames per CPU second of the rendering thread (CLOCK_THREAD_CPUTIME_ID)"},
        {"faster", faster},
        {"target_fps", kTargetFps},
        {"met", met},
        {"max_backend_diff_m", max_diff},
        {"pixels_over_0_1mm", pixels_over_0_1mm},
        {"pixels_compared", compared},
        {"laser_scans_per_s", laser_scans_per_s},
        {"laser_beams", laser.beam_count},
        {"laser_hit_fraction", hit_fraction},
        {"generate_s", generate_s},
        {"embree_build_s", embree_build_s},
        {"raster_index_build_s", raster_build_s},
        {"peak_rss_mb", peak_rss_mb},
        {"embree_threads", 1},
        {"raster_kernel", kernel_used},
        {"default_pylon_scene", scene_file},
        {"default_pylon_triangles", default_triangles},
        {"default_pylon_fps_raster", default_fps},
    };
    if (!out_path.empty()) {
      std::ofstream f(out_path);
      if (!f) throw ConfigError("--out = '" + out_path + "': cannot write it");
      f << report.dump(2) << "\n";
    }
    return kExitOk;
  });
}
