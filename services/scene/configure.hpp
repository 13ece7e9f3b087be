#pragma once
/// @file
/// climbsim-scene's configuration (docs/design.md#configuration): the run's scenario and the
/// command line's own options to the scene file, the scene model's parameters and the topics
/// written. climbsim-scene's main, climbsim solo and the launcher's depth layout check take
/// them from here; every default is SceneParams' (or, not given there, the scene camera's) or
/// this file's.

#include <optional>
#include <string>

#include "climbsim/scenario_and_robot.hpp"
#include "depth_frames.hpp"
#include "scene_model.hpp"

namespace climbsim::scene {

/// climbsim-scene's options besides --scenario/--set.
struct SceneOverrides {
  std::optional<std::string> scene_file;    ///< --scene (refused with a scenario); default: the build's pylon
  std::optional<std::string> pose_element;  ///< --pose-element
  std::optional<std::string> camera;        ///< --camera
  std::optional<std::string> laser;         ///< --laser
  std::string outputs = "depth,laser";      ///< --outputs: topics to write
  std::optional<int> depth_size_px;         ///< --depth-size-px, before the scenario's depth_camera.size_px
  std::optional<double> depth_width_m;      ///< --depth-width-m
  std::optional<double> near_m;             ///< --near
  std::optional<double> far_m;              ///< --far
  bool quantise_8bit = false;               ///< --quantise-8bit
  std::string backend = "rasterizer";       ///< --depth-backend: rasterizer or embree
};

/// The scenario's depth_camera.subpixel (false without a scenario): area-weighted edge pixels
/// here, sub-pixel strip shares in the sealing and in a --tile's shard
/// (docs/design.md#sub-pixel-leakage).
bool subpixelLeakage(const ScenarioAndRobot& run);

/// The model's parameters of `overrides` and `run` (its scenario may be empty: started without
/// one): the depth image's side is --depth-size-px, else the scenario's depth_camera.size_px
/// (when set, > 0), else the scene camera's; its side on the wall --depth-width-m, else the
/// scene camera's size, else the robot's view (robotDepthViewM); kSubpixelDepthSamplesPerPixel
/// rays over an edge pixel with subpixelLeakage, else 1, and then the robot's sealing.max_slope
/// for the edge pixels' support heights. The outputs leave the laser out unless
/// they name it. ConfigError for an unknown backend or output.
SceneParams sceneParams(const ScenarioAndRobot& run, const SceneOverrides& overrides);

/// Everything climbsim-scene's model and node are made of (but a --tile, which needs the
/// loaded scene: ShardTiles).
struct SceneSetup {
  std::string scene_file;  ///< the scenario's scene (resolved against the build directory), else --scene
  SceneParams params;      ///< sceneParams
  bool write_depth = false;
  bool write_laser = false;
  std::string robot_file;  ///< the scenario's robot ("" without a scenario): a --tile's shard
  bool subpixel = false;   ///< subpixelLeakage: a --tile's shard reads sub-pixel strip shares
  /// Which depth frames are whole (docs/design.md#what-the-scene-renders): with a scenario
  /// writing depth on the rasteriser, the whole sealing's pixels but at the frames a reader
  /// reads whole (the depth grid's, the sealing pictures', every frame with
  /// recording.depth_images); without one, every frame whole. SceneNode takes it (a --tile
  /// renders its shard's tiles instead).
  DepthFrameChoice frames;
  /// The run's robot body (surface::robotBodyMesh of its geometry) in the robot frame: what
  /// loadRunScene hangs under the robot's pose.
  LocalMesh robot_body;
};

/// The scene setup of `run` (its scenario may be empty) and `overrides`; a scenario's
/// "$BUILD/" scene is resolved against `build_dir`. ConfigErrors as sceneParams.
SceneSetup configureScene(const ScenarioAndRobot& run, const SceneOverrides& overrides, const std::string& build_dir);

/// The scene of `setup`: its scene file with the robot body under the robot's pose
/// (attachRobotBody: unless the scene's robot parts carry meshes of their own). ConfigErrors
/// as loadSceneDescription.
Scene loadRunScene(const SceneSetup& setup);

/// loadRunScene on `description`, setup.scene_file as loadSceneDescription read it (the
/// in-process runner reads it once for the scene and the drive).
Scene runSceneOf(SceneDescription description, const SceneSetup& setup);

}  // namespace climbsim::scene
