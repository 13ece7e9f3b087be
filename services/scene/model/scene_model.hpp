#pragma once
/// @file
/// The scene's sensors as a model of the one contract (docs/design.md#models,
/// docs/design.md#the-model-contract): Params (SceneParams and the loaded Scene), State
/// (SceneState: the robot pose in force), Inputs (SceneInputs: a new pose, and which sensors to
/// read), Outputs (SceneOutputs: the depth image, the laser scan) and `Outputs step(State&, const
/// Inputs&, t_ns, dt_ns)`.
///
/// Frames: the state holds T_W_R, the robot frame R in the wall frame W. In the scene, R is
/// the frame of the part the 3d Pose element (SceneParams::pose_element) is attached to and W
/// the frame of that part's parent; the element's pose replaces the part's offset, so T_W_R is
/// set as is.

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render_scene.hpp"
#include "climbsim/wall/scene.hpp"
#include "climbsim/model_contract.hpp"

namespace climbsim::scene {

/// Rays averaged over an edge pixel of the depth camera with sub-pixel leakage (the
/// scenario's depth_camera.subpixel, docs/design.md#sub-pixel-leakage).
constexpr int kSubpixelDepthSamplesPerPixel = 16;

/// What the model renders and from where. Values not given (std::nullopt) come from the
/// scene's camera and distance_sensor, or the renderer's defaults when the scene has none.
struct SceneParams {
  std::string pose_element = "robot_pose";  ///< 3d Pose element placed by the robot pose
  std::string camera = "depth_cam";         ///< scene camera giving the mount and defaults ("" or absent: R)
  std::string laser = "laser_scanner";      ///< scene distance_sensor of the scan ("": no scans)
  std::optional<int> depth_size_px;         ///< image side (square) [px]
  std::optional<double> depth_width_m;      ///< image side on the sealing plane [m]
  /// Image side on the sealing plane when neither depth_width_m nor the scene camera's size
  /// gives one [m]: the robot's view (climbsim/robot/depth_view.hpp); else the renderer's.
  std::optional<double> robot_view_m;
  std::optional<double> near_m;             ///< highest height seen [m], in the camera frame
  std::optional<double> far_m;              ///< lowest height reported [m]
  bool quantise_8bit = false;
  /// Rays averaged over a depth pixel an edge crosses (DepthCameraParams::samples_per_pixel):
  /// 1, one ray through each pixel's centre; kSubpixelDepthSamplesPerPixel with sub-pixel
  /// leakage, the area-weighted height of an edge pixel, so that the sealing's leakage follows
  /// the robot's pose (docs/design.md#sub-pixel-leakage).
  int depth_samples_per_pixel = 1;
  /// With depth_samples_per_pixel > 1: the sealing's max_slope [m/m], for each edge pixel's
  /// support height (DepthCameraParams::support_slope); 0: none.
  double depth_support_slope = 0.0;
  DepthBackend backend = DepthBackend::kRasterizer;
  PixelTile depth_tile;                     ///< render only this part of the image (whole by default)
  /// When set, each frame's tile instead (but those SceneInputs::depth_whole asks whole): the
  /// one it gives for the frame's height bound U [m] (near_m - headroom_m of the image, from
  /// RenderScene::depthHeightBound), e.g. the pixels a sealing shard can read when no height
  /// exceeds U (climbsim-scene --tile), or the whole sealing (node/shard_tile.hpp
  /// wholeSealingTiles: the default run, docs/design.md#what-the-scene-renders).
  std::function<PixelTile(double height_bound_m)> depth_tile_for_bound;
};

/// The camera parameters and the mount the params and the scene give: a scene camera
/// supplies width/height [px], size [m] and near/far (near_limit and far_limit are distances
/// along the view direction -z, so heights are their negatives); the params override.
/// ConfigError naming the option and value when the result is out of range.
DepthCameraParams depthCameraParams(const Scene& scene, const SceneParams& params);
/// The same from the scene's description alone (no meshes loaded): what the launcher checks
/// before a run starts.
DepthCameraParams depthCameraParams(const SceneDescription& scene, const SceneParams& params);

/// What evolves: the robot pose in force (held until a new one comes).
struct SceneState {
  Pose T_W_R = Pose::Identity();  ///< robot frame R in the wall frame W [m]
};

/// One step's inputs.
struct SceneInputs {
  std::optional<Pose> T_W_R;  ///< a new robot pose (finite, orthonormal), else the one in force is held
  bool depth = false;         ///< render the depth image
  bool laser = false;         ///< scan the laser (needs SceneParams::laser)
  /// Render the whole depth image even with SceneParams::depth_tile_for_bound (a frame some
  /// reader reads whole: model/depth_frames.hpp).
  bool depth_whole = false;
};

/// One step's outputs (those asked for).
struct SceneOutputs {
  std::optional<DepthImage> depth;  ///< in the camera frame; robot parts never in it
  std::optional<LaserScan> laser;   ///< from the scene's distance_sensor
  Pose T_W_S = Pose::Identity();    ///< the laser scanner in W (with a scan)
};

/// The scene graph and the renderer for one scene. Everything that evolves is in the caller's
/// SceneState: step() places the robot from the state before it renders, so the scene graph's
/// pose and the renderer's body poses are caches of the state, never read before being set.
/// They stay in the model (the renderer's acceleration structures hold the body poses: a copy
/// per state would copy the scene), used under a lock: the model is thread-safe, one model may
/// serve several states (calls serialised; each state's outputs are those it would get alone).
///
/// Time: the scene has no dynamics. What step() renders is a function of the pose in force
/// and the scene alone (the robot moves by new poses in the inputs, not by time), so t_ns and
/// dt_ns of the contract's step are not used; they are there so that every model is stepped
/// alike (docs/design.md#the-model-contract).
class SceneModel {
 public:
  /// The model contract's types (climbsim/model_contract.hpp).
  using Params = SceneParams;
  using State = SceneState;
  using Inputs = SceneInputs;
  using Outputs = SceneOutputs;

  /// Hands the scene's static triangles and moving parts to the renderer. ConfigError if the
  /// pose element or the laser sensor is missing, or the camera parameters are bad.
  SceneModel(Scene scene, const SceneParams& params);

  /// The robot at the pose element's part offset of the scene file.
  SceneState initialState() const;
  /// Takes inputs.T_W_R into the state (if given) and renders what inputs asks for at the
  /// state's pose. t_ns and dt_ns [ns] are not used (no dynamics: see the class comment).
  /// ConfigError for a laser scan without a distance_sensor.
  SceneOutputs step(SceneState& state, const SceneInputs& inputs, std::int64_t t_ns, std::int64_t dt_ns) const;

  /// Renders only `tile` of the depth image from now on. ConfigError for a tile outside it.
  void setDepthTile(const PixelTile& tile);

  /// T_W_S of the laser scanner and T_world_C of the depth camera with the robot at `state`.
  Pose scannerPoseInWall(const SceneState& state) const;
  Pose cameraPose(const SceneState& state) const;

  const DepthCameraParams& camera() const { return camera_params_; }
  const Scene& scene() const { return scene_; }
  /// Part ids left out of the depth image (the subtree the pose element moves).
  const std::vector<std::uint32_t>& robotPartIds() const { return robot_ids_; }
  std::size_t staticTriangleCount() const { return renderer_->staticTriangleCount(); }

 private:
  void place(const SceneState& state) const;
  std::vector<std::uint32_t> hiddenParts(bool with_robot) const;

  mutable Scene scene_;  ///< its robot pose: a cache of the state (place)
  SceneParams params_;
  DepthCameraParams camera_params_;
  LaserParams laser_params_;
  std::size_t robot_part_ = 0;
  std::size_t wall_part_ = 0;
  std::optional<std::size_t> camera_index_;
  std::optional<std::size_t> laser_index_;
  std::vector<std::uint32_t> robot_ids_;
  std::unique_ptr<RenderScene> renderer_;  ///< its body poses: a cache of the state (place)
  std::vector<std::pair<std::uint32_t, RenderScene::BodyId>> bodies_;  ///< moving part -> body
  /// Guards the caches of the state (scene_'s robot pose, renderer_'s body poses).
  mutable std::recursive_mutex cache_mutex_;
};

static_assert(is_model_v<SceneModel>, "SceneModel keeps the model contract");

}  // namespace climbsim::scene
