#include "crack_descent_frames.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/scenario_and_robot.hpp"
#include "scene/configure.hpp"
#include "depth_rasterizer.hpp"
#include "render_scene.hpp"
#include "scene_node.hpp"
#include "scene_translate.hpp"

namespace climbsim::bench {

namespace {

using json = nlohmann::json;
using scene::DepthCameraParams;
using scene::DepthImage;
using scene::Pose;

constexpr double kPi = 3.14159265358979323846;
/// What a depth frame of the default run may cost [ms of one core].
constexpr double kTargetMs = 0.25;
/// crack-descent's depth period: 50 frames/s [ns].
constexpr std::int64_t kFramePeriod_ns = 20'000'000;

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// A renderer of the run's scene as the scene model builds it: the static wall, and the
/// moving parts as bodies at their poses (hidden from the depth camera as the robot's parts).
scene::RenderScene renderer(const scene::Scene& loaded, bool reference) {
  scene::RenderOptions options;
  options.reference_raster = reference;
  scene::RenderScene sensors(loaded.staticMesh(), options);
  for (const auto& part : loaded.movingParts()) {
    scene::TriangleMesh mesh_B;
    mesh_B.vertices_m = part.mesh->vertices_m;
    mesh_B.triangles = part.mesh->triangles;
    mesh_B.part_ids.assign(mesh_B.triangles.size(), part.part);
    sensors.addBody(mesh_B, part.T_world_part);
  }
  return sensors;
}

/// The machine's load average over the last minute (-1 if unknown).
double loadAverage() {
  double load[1] = {-1.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

struct PathCost {
  double cpu_ms = 0.0;                          ///< per frame, this thread
  std::uint64_t fnv = 14695981039346656037ull;  ///< FNV-1a of every frame's pixel bits
  std::uint64_t supports_fnv = 14695981039346656037ull;  ///< FNV-1a of every frame's supports (pixels, bits)
  std::vector<DepthImage> images;               ///< every frame (compared afterwards, not timed)
  double triangles = 0.0;                       ///< handed to the kernel per frame (its counters)
  double sample_triangles_set_up = 0.0;         ///< of those, set up for the sample passes per frame
};

PathCost run(scene::RenderScene& sensors, const std::vector<Pose>& poses, const DepthCameraParams& camera,
             const std::vector<std::uint32_t>& hidden) {
  PathCost cost;
  DepthImage image;
  sensors.renderDepth(poses.front(), camera, hidden, image);  // warm-up
  const double cpu0 = threadCpuSeconds();
  for (const Pose& T : poses) sensors.renderDepth(T, camera, hidden, image);
  cost.cpu_ms = 1e3 * (threadCpuSeconds() - cpu0) / static_cast<double>(poses.size());
  for (const Pose& T : poses) {  // not timed
    sensors.renderDepth(T, camera, hidden, image);
    cost.triangles += static_cast<double>(sensors.lastDepthCounters().triangles) / static_cast<double>(poses.size());
    cost.sample_triangles_set_up +=
        static_cast<double>(sensors.lastDepthCounters().sample_triangles_set_up) / static_cast<double>(poses.size());
    const auto* bytes = reinterpret_cast<const unsigned char*>(image.height_m.data());
    for (std::size_t i = 0; i < image.height_m.size() * sizeof(float); ++i) cost.fnv = (cost.fnv ^ bytes[i]) * 1099511628211ull;
    const auto hashSupports = [&](const auto& values) {
      const auto* support_bytes = reinterpret_cast<const unsigned char*>(values.data());
      for (std::size_t i = 0; i < values.size() * sizeof(values[0]); ++i) {
        cost.supports_fnv = (cost.supports_fnv ^ support_bytes[i]) * 1099511628211ull;
      }
    };
    hashSupports(image.support_px);
    hashSupports(image.support_m);
    cost.images.push_back(image);
  }
  return cost;
}

/// Where a reference frame's CPU goes [ms per frame]: the z-buffer's clear, the walk of the
/// triangle index down to the leaves in view, the kernel (set-up and pixel tests of every
/// batch of those leaves) and the copy into the image (at least far).
struct Breakdown {
  double clear_ms = 0.0, walk_ms = 0.0, kernel_ms = 0.0, copy_ms = 0.0;
  double leaves = 0.0, triangles = 0.0;  ///< per frame
};

Breakdown breakdown(const scene::Scene& loaded, const std::vector<Pose>& poses, const DepthCameraParams& camera) {
  std::vector<std::uint32_t> slots(loaded.staticMesh().triangles.size(), 0);
  const scene::TriangleIndex index(loaded.staticMesh(), slots);
  const std::vector<char> excluded;
  std::vector<float> z(static_cast<std::size_t>(camera.width_px) * camera.height_px);
  std::vector<float> image(z.size());
  const auto far = static_cast<float>(camera.far_m);
  Breakdown b;
  double t = threadCpuSeconds();
  const auto lap = [&](double& into) {
    const double now = threadCpuSeconds();
    into += now - t;
    t = now;
  };
  std::size_t leaves = 0;
  scene::RasterCounters counters;
  for (const Pose& T_W_C : poses) {
    const Pose T_C_W = T_W_C.inverse();
    t = threadCpuSeconds();
    z.assign(z.size(), -std::numeric_limits<float>::infinity());
    lap(b.clear_ms);
    const double s = camera.pixel_size_m;
    index.forEachLeafInView(T_C_W.linear(), T_C_W.translation(), 0.5 * camera.width_px * s, 0.5 * camera.height_px * s,
                            camera.far_m, camera.near_m, [&](const scene::TriangleIndex::Leaf&) { ++leaves; });
    lap(b.walk_ms);
    scene::rasterizeDepth(index, T_C_W, camera, excluded, z, scene::RasterKernel::kAuto, &counters, true);
    lap(b.kernel_ms);
    for (std::size_t i = 0; i < z.size(); ++i) image[i] = std::max(z[i], far);
    lap(b.copy_ms);
  }
  const double n = static_cast<double>(poses.size());
  b.kernel_ms -= b.walk_ms;  // rasterizeDepth walks the index too
  for (double* ms : {&b.clear_ms, &b.walk_ms, &b.kernel_ms, &b.copy_ms}) *ms *= 1e3 / n;
  b.leaves = static_cast<double>(counters.leaves) / n;
  b.triangles = static_cast<double>(counters.triangles) / n;
  return b;
}

/// The default run's frames (SceneNode with the scenario's DepthFrameChoice: the whole sealing's
/// pixels, whole at the frames read whole), CPU ms per frame of the node's renderDepthAt, by kind.
struct DefaultRunCost {
  double cpu_ms = 0.0;         ///< per frame, every frame: the masked and whole frames by their share
  double masked_cpu_ms = 0.0;  ///< per masked frame
  double whole_cpu_ms = 0.0;   ///< per whole frame
  int whole_frames = 0;
  double masked_pixels = 0.0;  ///< rendered per masked frame (the mask's pixels)
  std::size_t differing = 0;   ///< frames with a pixel (whole, or of the mask) unlike the whole image's
  /// Per masked frame, the renderer alone on the same masks (no height bound, no choice of mask).
  double mask_render_cpu_ms = 0.0;
  double masked_triangles = 0.0;  ///< handed to the kernel per masked frame (the renderer's counters)
  double masked_set_up = 0.0;     ///< of those, set up over the pixel centres per masked frame
};

DefaultRunCost defaultRun(const scene::SceneSetup& setup, const scene::DepthFrameChoice& choice,
                          const std::vector<climbsim::RobotState>& states,
                          const std::vector<DepthImage>& whole_images, std::int64_t frame_period_ns,
                          scene::RenderScene& sensors, const std::vector<Pose>& poses, const DepthCameraParams& camera,
                          const std::vector<std::uint32_t>& hidden) {
  scene::SceneNode node(scene::loadRunScene(setup), setup.params, choice);
  DefaultRunCost cost;
  double masked_s = 0.0, whole_s = 0.0;
  std::vector<DepthImage> images;
  images.reserve(states.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    node.applyRobotStates({states[k]});
    const double cpu0 = threadCpuSeconds();
    DepthImage image = node.renderDepthAt(static_cast<std::int64_t>(k) * frame_period_ns);
    const double spent_s = threadCpuSeconds() - cpu0;
    (node.lastDepthWhole() ? whole_s : masked_s) += spent_s;
    cost.whole_frames += node.lastDepthWhole() ? 1 : 0;
    images.push_back(std::move(image));
  }
  const int frames = static_cast<int>(states.size());
  const int masked = frames - cost.whole_frames;
  cost.cpu_ms = 1e3 * (masked_s + whole_s) / frames;
  cost.masked_cpu_ms = masked > 0 ? 1e3 * masked_s / masked : 0.0;
  cost.whole_cpu_ms = cost.whole_frames > 0 ? 1e3 * whole_s / cost.whole_frames : 0.0;
  double mask_s = 0.0;
  DepthImage again;
  for (std::size_t k = 0; k < images.size(); ++k) {
    if (images[k].tile.whole()) continue;
    DepthCameraParams masked_camera = camera;
    masked_camera.tile = images[k].tile;
    const double cpu0 = threadCpuSeconds();
    sensors.renderDepth(poses[k], masked_camera, hidden, again);
    mask_s += threadCpuSeconds() - cpu0;
    cost.masked_triangles += static_cast<double>(sensors.lastDepthCounters().triangles);
    cost.masked_set_up += static_cast<double>(sensors.lastDepthCounters().triangles_set_up);
  }
  if (masked > 0) {
    cost.masked_triangles /= masked;
    cost.masked_set_up /= masked;
  }
  cost.mask_render_cpu_ms = masked > 0 ? 1e3 * mask_s / masked : 0.0;
  for (std::size_t k = 0; k < images.size(); ++k) {  // not timed: each frame's pixels against the whole image's
    const DepthImage& image = images[k];
    const DepthImage& whole = whole_images[k];
    bool differs = false;
    if (image.tile.whole()) {
      differs = std::memcmp(image.height_m.data(), whole.height_m.data(), whole.height_m.size() * sizeof(float)) != 0;
    } else if (image.tile.mask) {
      cost.masked_pixels += static_cast<double>(image.tile.mask->count()) / masked;
      for (int r = image.tile.row0; r < image.tile.row0 + image.tile.rows; ++r) {
        for (int c = image.tile.col0; c < image.tile.col0 + image.tile.cols; ++c) {
          if (!image.tile.mask->contains(r, c)) continue;
          const float a = image.at(r, c), b = whole.at(r, c);
          differs = differs || std::memcmp(&a, &b, sizeof(float)) != 0;
        }
      }
    }
    cost.differing += differs;
  }
  return cost;
}

/// Frames whose pixels or supports differ in any bit between the two paths.
std::size_t differingFrames(const PathCost& a, const PathCost& b) {
  std::size_t differ = 0;
  for (std::size_t f = 0; f < a.images.size(); ++f) {
    const auto& x = a.images[f].height_m;
    const auto& y = b.images[f].height_m;
    const auto& xs = a.images[f].support_m;
    const auto& ys = b.images[f].support_m;
    differ += x.size() != y.size() || std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) != 0 ||
              a.images[f].support_px != b.images[f].support_px || xs.size() != ys.size() ||
              std::memcmp(xs.data(), ys.data(), xs.size() * sizeof(float)) != 0;
  }
  return differ;
}

}  // namespace

int crackDescentFrames(const std::string& scenario_file, const std::string& build_dir, int frames,
                       const std::string& out_path, bool subpixel_only, bool masked_only) {
  const ScenarioAndRobot run_setup = loadScenarioAndRobot(scenario_file, {});
  scene::SceneOverrides overrides;
  overrides.outputs = "depth";
  const scene::SceneSetup setup = scene::configureScene(run_setup, overrides, build_dir);
  scene::SceneNode node(scene::loadRunScene(setup), setup.params);
  std::vector<climbsim::RobotState> states;
  // crack-descent: held at (1.0, 1.2) with R's x down the wall (yaw -90°) for 2 s, then down
  // at 0.05 m/s; a depth frame every 20 ms (50 Hz); the camera poses as the scene service
  // places them.
  std::vector<Pose> camera_poses;
  for (int k = 0; k < frames; ++k) {
    const double t_s = 0.02 * k;  // kFramePeriod_ns
    Pose T = Pose::Identity();
    // As the run's trace has them: the sealing plane about 1 mm into the rough wall's mean,
    // pitched by up to 1 mrad while it drives.
    const double pitch_rad = t_s > 2.0 ? 1e-3 * std::sin(3.0 * t_s) : 0.0;
    T.linear() = (Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(1.0, 1.2 - 0.05 * std::max(0.0, t_s - 2.0), -0.001);
    auto state = scene::robotStateToIdl(T);
    state.source("drive");
    node.applyRobotStates({state});
    states.push_back(state);
    camera_poses.push_back(node.cameraPose());
  }
  const std::vector<std::uint32_t>& hidden = node.robotPartIds();
  DepthCameraParams centre = node.camera();
  centre.samples_per_pixel = 1;
  DepthCameraParams subpixel = centre;
  subpixel.samples_per_pixel = scene::kSubpixelDepthSamplesPerPixel;

  scene::RenderScene fast = renderer(node.scene(), false);
  if (subpixel_only) {
    const PathCost only = run(fast, camera_poses, subpixel, hidden);
    std::printf("bench: scene: crack-descent render_ms_subpixel=%.3f pixels_fnv=%016llx supports_fnv=%016llx "
                "triangles=%.0f sample_triangles_set_up=%.0f (%d samples per edge pixel, the default path alone)\n",
                only.cpu_ms, static_cast<unsigned long long>(only.fnv), static_cast<unsigned long long>(only.supports_fnv),
                only.triangles, only.sample_triangles_set_up, subpixel.samples_per_pixel);
    return kExitOk;
  }
  if (masked_only) {
    // The default run's masks (the node's choice per frame), then the renderer alone on them.
    scene::SceneNode run_node(scene::loadRunScene(setup), setup.params, setup.frames);
    const DepthCameraParams& run_camera = node.camera().samples_per_pixel > 1 ? subpixel : centre;
    std::vector<Pose> poses;
    std::vector<DepthCameraParams> cameras;
    for (std::size_t k = 0; k < states.size(); ++k) {
      run_node.applyRobotStates({states[k]});
      const DepthImage image = run_node.renderDepthAt(static_cast<std::int64_t>(k) * kFramePeriod_ns);
      if (image.tile.whole()) continue;
      poses.push_back(camera_poses[k]);
      cameras.push_back(run_camera);
      cameras.back().tile = image.tile;
    }
    PathCost only;
    DepthImage image;
    constexpr int kRounds = 10;  // the frames' CPU well above the set-up's for a profiler
    const double cpu0 = threadCpuSeconds();
    for (int round = 0; round < kRounds; ++round) {
      for (std::size_t k = 0; k < poses.size(); ++k) fast.renderDepth(poses[k], cameras[k], hidden, image);
    }
    only.cpu_ms = 1e3 * (threadCpuSeconds() - cpu0) / static_cast<double>(std::max<std::size_t>(kRounds * poses.size(), 1));
    // The height bound the scene model computes before each masked frame (its tile's choice).
    const double bound0 = threadCpuSeconds();
    double bound_sum = 0.0;
    for (int round = 0; round < kRounds; ++round) {
      for (std::size_t k = 0; k < poses.size(); ++k) bound_sum += fast.depthHeightBound(poses[k], run_camera, hidden);
    }
    const double bound_ms = 1e3 * (threadCpuSeconds() - bound0) / static_cast<double>(std::max<std::size_t>(kRounds * poses.size(), 1));
    double set_up = 0.0;
    for (std::size_t k = 0; k < poses.size(); ++k) {  // not timed
      fast.renderDepth(poses[k], cameras[k], hidden, image);
      only.triangles += static_cast<double>(fast.lastDepthCounters().triangles) / static_cast<double>(poses.size());
      set_up += static_cast<double>(fast.lastDepthCounters().triangles_set_up) / static_cast<double>(poses.size());
      const auto* bytes = reinterpret_cast<const unsigned char*>(image.height_m.data());
      for (std::size_t i = 0; i < image.height_m.size() * sizeof(float); ++i) only.fnv = (only.fnv ^ bytes[i]) * 1099511628211ull;
    }
    std::printf("bench: scene: crack-descent render_ms_masked_renderer=%.3f masked_frames=%zu pixels_fnv=%016llx "
                "triangles=%.0f set_up_over_centres=%.0f height_bound_ms=%.3f (sum %.6f) (the default run's masked "
                "frames 10 times over, the renderer alone)\n",
                only.cpu_ms, poses.size(), static_cast<unsigned long long>(only.fnv), only.triangles, set_up, bound_ms,
                bound_sum);
    return kExitOk;
  }
  scene::RenderScene reference = renderer(node.scene(), true);
  const PathCost fast_centre = run(fast, camera_poses, centre, hidden);
  const PathCost reference_centre = run(reference, camera_poses, centre, hidden);
  const PathCost fast_subpixel = run(fast, camera_poses, subpixel, hidden);
  const PathCost reference_subpixel = run(reference, camera_poses, subpixel, hidden);
  const Breakdown parts = breakdown(node.scene(), camera_poses, centre);
  const std::size_t differ_centre = differingFrames(fast_centre, reference_centre);
  const std::size_t differ_subpixel = differingFrames(fast_subpixel, reference_subpixel);
  // The scene node's every frame whole (no choice) on the same frames: what the default run's
  // frames cost without masks, node included (pose placing, hidden parts).
  // The run's camera: 16 rays per edge pixel with the scenario's depth_camera.subpixel.
  const bool run_subpixel = node.camera().samples_per_pixel > 1;
  const DepthCameraParams& run_camera = run_subpixel ? subpixel : centre;
  const std::vector<DepthImage>& run_images = run_subpixel ? fast_subpixel.images : fast_centre.images;
  const DefaultRunCost all_whole = defaultRun(setup, scene::DepthFrameChoice{}, states, run_images, kFramePeriod_ns, fast,
                                              camera_poses, run_camera, hidden);
  const DefaultRunCost default_run = defaultRun(setup, setup.frames, states, run_images, kFramePeriod_ns, fast,
                                                camera_poses, run_camera, hidden);

  std::printf("bench: scene: crack-descent render_ms=%.3f target_ms=%.2f met=%s render_ms_whole=%.3f "
              "render_ms_masked=%.3f (renderer alone %.3f, %.0f triangles, %.0f set up over the centres) whole_frames=%d/%d (%.3f ms each) masked_pixels=%.0f/%d "
              "differing_frames=%zu/%d (the default run's frames: the whole sealing's pixels, whole every 0.1 s and at the "
              "sealing pictures; every frame whole through the scene node: %.3f)\n",
              default_run.cpu_ms, kTargetMs, default_run.cpu_ms <= kTargetMs ? "yes" : "no", fast_centre.cpu_ms,
              default_run.masked_cpu_ms, default_run.mask_render_cpu_ms, default_run.masked_triangles, default_run.masked_set_up,
              default_run.whole_frames, frames,
              default_run.whole_cpu_ms, default_run.masked_pixels,
              centre.width_px * centre.height_px, default_run.differing, frames, all_whole.cpu_ms);

  std::printf("bench: scene: crack-descent render_ms_whole=%.3f reference_render_ms=%.3f "
              "speedup=%.2f differing_frames=%zu/%d pixels_fnv=%016llx triangles=%.0f reference_triangles=%.0f (%d x %d px, "
              "%zu static triangles, raster_kernel=%s)\n",
              fast_centre.cpu_ms, reference_centre.cpu_ms,
              reference_centre.cpu_ms / fast_centre.cpu_ms, differ_centre, frames,
              static_cast<unsigned long long>(fast_centre.fnv), fast_centre.triangles, reference_centre.triangles,
              centre.width_px, centre.height_px,
              fast.staticTriangleCount(), scene::rasterKernelName());
  std::printf("bench: scene: crack-descent render_ms_subpixel=%.3f reference_render_ms_subpixel=%.3f speedup=%.2f "
              "over_centre_rays=%.2f differing_frames=%zu/%d pixels_fnv=%016llx supports_fnv=%016llx triangles=%.0f "
              "sample_triangles_set_up=%.0f reference_triangles=%.0f (%d samples per edge pixel)\n",
              fast_subpixel.cpu_ms, reference_subpixel.cpu_ms, reference_subpixel.cpu_ms / fast_subpixel.cpu_ms,
              fast_subpixel.cpu_ms / fast_centre.cpu_ms, differ_subpixel, frames,
              static_cast<unsigned long long>(fast_subpixel.fnv),
              static_cast<unsigned long long>(fast_subpixel.supports_fnv), fast_subpixel.triangles,
              fast_subpixel.sample_triangles_set_up, reference_subpixel.triangles,
              subpixel.samples_per_pixel);
  std::printf("bench: scene: crack-descent reference_breakdown_ms clear=%.3f index_walk=%.3f kernel=%.3f copy=%.3f "
              "(leaves=%.0f triangles=%.0f per frame, of reference_render_ms=%.3f)\n",
              parts.clear_ms, parts.walk_ms, parts.kernel_ms, parts.copy_ms, parts.leaves, parts.triangles,
              reference_centre.cpu_ms);
  const json report{{"name", "scene-crack-descent"},
                    {"frames", frames},
                    {"width_px", centre.width_px},
                    {"target_ms", kTargetMs},
                    {"render_ms", default_run.cpu_ms},
                    {"render_ms_whole", fast_centre.cpu_ms},
                    {"render_ms_masked", default_run.masked_cpu_ms},
                    {"render_ms_masked_renderer_alone", default_run.mask_render_cpu_ms},
                    {"triangles_per_masked_frame", default_run.masked_triangles},
                    {"centre_triangles_set_up_per_masked_frame", default_run.masked_set_up},
                    {"render_ms_whole_in_default_run", default_run.whole_cpu_ms},
                    {"render_ms_every_frame_whole_node", all_whole.cpu_ms},
                    {"whole_frames", default_run.whole_frames},
                    {"masked_pixels_per_frame", default_run.masked_pixels},
                    {"differing_frames_default_run", default_run.differing},
                    {"reference_render_ms", reference_centre.cpu_ms},
                    {"render_ms_subpixel", fast_subpixel.cpu_ms},
                    {"reference_render_ms_subpixel", reference_subpixel.cpu_ms},
                    {"differing_frames", differ_centre},
                    {"triangles_per_frame", fast_centre.triangles},
                    {"triangles_per_frame_subpixel", fast_subpixel.triangles},
                    {"sample_triangles_set_up_per_frame", fast_subpixel.sample_triangles_set_up},
                    {"reference_triangles_per_frame_subpixel", reference_subpixel.triangles},
                    {"reference_breakdown_ms",
                     {{"clear", parts.clear_ms}, {"index_walk", parts.walk_ms}, {"kernel", parts.kernel_ms},
                      {"copy", parts.copy_ms}}},
                    {"leaves_per_frame", parts.leaves},
                    {"reference_triangles_per_frame", parts.triangles},
                    {"differing_frames_subpixel", differ_subpixel},
                    {"timing", "CPU ms per frame of the rendering thread (CLOCK_THREAD_CPUTIME_ID)"},
                    {"loadavg", loadAverage()}};
  if (!out_path.empty()) {
    std::ofstream f(out_path);
    if (!f) throw ConfigError("--out = '" + out_path + "': cannot write it");
    f << report.dump(2) << "\n";
  }
  return differ_centre + differ_subpixel + default_run.differing == 0 ? kExitOk : 1;
}

}  // namespace climbsim::bench
