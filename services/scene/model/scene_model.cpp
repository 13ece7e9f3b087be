#include "scene_model.hpp"

#include <algorithm>
#include <cmath>

#include "climbsim/cache_files.hpp"
#include "climbsim/errors.hpp"

namespace climbsim::scene {

DepthCameraParams depthCameraParams(const Scene& scene, const SceneParams& options) {
  return depthCameraParams(scene.description(), options);
}

DepthCameraParams depthCameraParams(const SceneDescription& scene, const SceneParams& options) {
  DepthCameraParams params;
  double side_m = options.robot_view_m.value_or(params.pixel_size_m * params.width_px);
  if (!options.camera.empty()) {
    const auto found = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                                    [&](const CameraInfo& c) { return c.name == options.camera; });
    if (found == scene.cameras.end()) throw ConfigError("scene " + scene.file + ": no camera named '" + options.camera + "'");
    const CameraInfo& cam = *found;
    if (cam.width_px > 0) params.width_px = cam.width_px;
    params.height_px = cam.height_px > 0 ? cam.height_px : params.width_px;
    if (cam.width_m > 0.0) side_m = cam.width_m;
    params.near_m = -cam.near_limit_m;
    if (cam.far_limit_m != 0.0) params.far_m = -cam.far_limit_m;
  }
  if (options.depth_size_px) {
    if (*options.depth_size_px < 1 || *options.depth_size_px > kMaxDepthImageSidePx) {
      throw ConfigError("--depth-size-px = " + std::to_string(*options.depth_size_px) + ": must be 1.." +
                        std::to_string(kMaxDepthImageSidePx));
    }
    params.width_px = params.height_px = *options.depth_size_px;
  }
  if (options.depth_width_m) {
    if (!(*options.depth_width_m > 0.0) || !std::isfinite(*options.depth_width_m)) {
      throw ConfigError("--depth-width-m = " + std::to_string(*options.depth_width_m) + ": must be > 0");
    }
    side_m = *options.depth_width_m;
  }
  params.pixel_size_m = side_m / params.width_px;
  if (options.near_m) params.near_m = *options.near_m;
  if (options.far_m) params.far_m = *options.far_m;
  if (!(params.near_m > params.far_m) || !std::isfinite(params.near_m) || !std::isfinite(params.far_m)) {
    throw ConfigError("depth camera: near " + std::to_string(params.near_m) + " m must be above far " +
                      std::to_string(params.far_m) + " m (--near, --far or the scene camera's limits)");
  }
  params.quantised_8bit = options.quantise_8bit;
  params.samples_per_pixel = options.depth_samples_per_pixel;
  params.support_slope = options.depth_support_slope;
  params.tile = options.depth_tile;
  params.validate();
  return params;
}

SceneModel::SceneModel(Scene scene, const SceneParams& params)
    : scene_(std::move(scene)), params_(params), camera_params_(depthCameraParams(scene_, params)) {
  const PoseElement& pose = scene_.poseElement(params.pose_element);
  robot_part_ = static_cast<std::size_t>(pose.part);
  wall_part_ = static_cast<std::size_t>(scene_.parts()[robot_part_].parent);
  robot_ids_ = scene_.partsMovedBy(params.pose_element);
  const auto& cameras = scene_.description().cameras;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    if (cameras[i].name == params.camera) camera_index_ = i;
  }
  const auto& lasers = scene_.description().distance_sensors;
  for (std::size_t i = 0; i < lasers.size(); ++i) {
    if (lasers[i].name == params.laser) laser_index_ = i;
  }
  if (!params.laser.empty()) {
    const DistanceSensorInfo& laser = scene_.distanceSensor(params.laser);
    laser_params_ = LaserParams::fromScanRange(laser.scan_angle_range_rad * 180.0 / M_PI,
                                               laser.angular_resolution_rad * 180.0 / M_PI, laser.max_distance_m);
  }
  RenderOptions render_options;
  render_options.depth_backend = params.backend;
  // Embree casts the laser's beams (and renders depth when it is the backend); building its
  // BVH over the static mesh is most of the loading, so a scene without either goes without.
  render_options.embree = !params.laser.empty() || params.backend == DepthBackend::kEmbree;
  render_options.index_cache_dir = cacheDir();
  renderer_ = std::make_unique<RenderScene>(scene_.staticMesh(), render_options);
  for (const auto& part : scene_.movingParts()) {
    TriangleMesh mesh_B;
    mesh_B.vertices_m = part.mesh->vertices_m;
    mesh_B.triangles = part.mesh->triangles;
    mesh_B.part_ids.assign(mesh_B.triangles.size(), part.part);
    bodies_.emplace_back(part.part, renderer_->addBody(mesh_B, part.T_world_part));
  }
}

SceneState SceneModel::initialState() const {
  // The constructor has set no pose yet: the part's local pose is the scene file's offset.
  SceneState state;
  state.T_W_R = scene_.localPose(robot_part_);
  return state;
}

void SceneModel::place(const SceneState& state) const {
  scene_.setPose(params_.pose_element, state.T_W_R);
  for (const auto& [part, body] : bodies_) renderer_->setBodyPose(body, scene_.worldPose(part));
}

std::vector<std::uint32_t> SceneModel::hiddenParts(bool with_robot) const {
  std::vector<std::uint32_t> hidden = with_robot ? robot_ids_ : std::vector<std::uint32_t>{};
  for (const auto& [part, body] : bodies_) {
    if (!scene_.visible(part)) hidden.push_back(part);
  }
  return hidden;
}

SceneOutputs SceneModel::step(SceneState& state, const SceneInputs& inputs, std::int64_t /*t_ns: no dynamics*/,
                              std::int64_t /*dt_ns: no dynamics*/) const {
  if (inputs.T_W_R) state.T_W_R = *inputs.T_W_R;
  if (inputs.laser && !laser_index_) throw ConfigError("scene: no distance_sensor to scan with (--laser)");
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  place(state);
  SceneOutputs out;
  if (inputs.depth) {
    out.depth.emplace();
    const Pose T_W_C = cameraPose(state);
    const std::vector<std::uint32_t> hidden = hiddenParts(true);
    if (params_.depth_tile_for_bound && !inputs.depth_whole) {
      // The tile for the bound exactly as a reader computes it from the sample (near - headroom).
      const double headroom_m = camera_params_.near_m - renderer_->depthHeightBound(T_W_C, camera_params_, hidden);
      DepthCameraParams camera = camera_params_;
      camera.tile = params_.depth_tile_for_bound(camera.near_m - headroom_m);
      camera.validate();
      renderer_->renderDepth(T_W_C, camera, hidden, *out.depth);
      out.depth->headroom_m = headroom_m;
      // A support height comes from the same geometry as the bound; the clamp only keeps a
      // sample just outside the view from passing it (a shard's tile is chosen for the bound).
      const auto bound = static_cast<float>(camera.near_m - headroom_m);
      for (float& v : out.depth->support_m) v = std::min(v, bound);
    } else {
      renderer_->renderDepth(T_W_C, camera_params_, hidden, *out.depth);
    }
  }
  if (inputs.laser) {
    out.laser.emplace();
    renderer_->scanLaser(scene_.sensorPose(params_.laser), laser_params_, hiddenParts(false), *out.laser);
    out.T_W_S = scannerPoseInWall(state);
  }
  return out;
}

void SceneModel::setDepthTile(const PixelTile& tile) {
  DepthCameraParams params = camera_params_;
  params.tile = tile;
  params.validate();
  camera_params_ = params;
}

Pose SceneModel::cameraPose(const SceneState& state) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  scene_.setPose(params_.pose_element, state.T_W_R);
  return camera_index_ ? scene_.sensorPose(params_.camera) : scene_.worldPose(robot_part_);
}

Pose SceneModel::scannerPoseInWall(const SceneState& state) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  scene_.setPose(params_.pose_element, state.T_W_R);
  return scene_.worldPose(wall_part_).inverse() * scene_.sensorPose(params_.laser);
}

}  // namespace climbsim::scene
