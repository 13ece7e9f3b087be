#pragma once
/// @file
/// Which wheels of the drive stand over nothing: no scene surface under their contact point
/// (past the edge of the scene, or over a hole deeper than the depth camera reaches; see
/// climbsim/wall/wall_coverage.hpp). With the wheels on the scene's surface (wheel_ground.hpp)
/// such a wheel has no contact unless the rim of the hole is within its radius; with the
/// simbody backend (the wall plane) it is still pressed on and grips. Either way the run says
/// so at the step it happens (docs/design.md#drive).

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drive_params.hpp"
#include "drive_types.hpp"
#include "climbsim/wall/scene_description.hpp"
#include "climbsim/wall/surface_heights.hpp"
#include "climbsim/wall/wall_coverage.hpp"
#include "wheel_ground.hpp"

namespace climbsim::drive {

class WheelsOverScene {
 public:
  /// `wheels`: the contact points in R (DriveParams::wheels).
  WheelsOverScene(scene::WallCoverage coverage, std::vector<WheelMount> wheels);

  /// The contact point of wheel `w` in the wall plane (x, y of W) [m] at the pose of `outputs`:
  /// p_W = position + R(q) (x, y, 0).
  std::array<double, 2> contactPoint(const DriveOutputs& outputs, std::size_t w) const;

  /// The wheels (0-based) over nothing at `outputs` that were not named before: each wheel is
  /// named once per run, at the first step it is over nothing.
  std::vector<std::size_t> newlyOverNothing(const DriveOutputs& outputs);

  const scene::WallCoverage& coverage() const { return coverage_; }

  /// "wheel N stands over nothing at t = T s: ..." for wheel `w` (0-based) at `outputs`, at
  /// simulation time t_ns (the end of the step that found it; T with 3 decimals): the line the
  /// launcher reads into summary.json's wheels_over_nothing (and climbsim solo writes there).
  std::string overNothingText(const DriveOutputs& outputs, std::size_t w, std::int64_t t_ns) const;

 private:
  scene::WallCoverage coverage_;
  std::vector<WheelMount> wheels_;
  std::vector<char> named_;
};

/// The scene XML a run's drive reads once, for the wheel check and the surface under the
/// wheels: its parts, the 3d Pose element that places the robot ("robot_pose", the scene
/// service's default, or its only one) and how deep a surface still counts (coverageReach).
struct WheelScene {
  explicit WheelScene(const std::string& scene_file);
  /// The same from the scene file as loadSceneDescription read it (description.file).
  explicit WheelScene(scene::SceneDescription description);
  std::string scene_file;
  std::string pose_element;
  double reach_m = 0.0;
  std::shared_ptr<const scene::Scene> world;
};

/// A WheelScene loading (or loaded, or failed with what loading threw).
using WheelSceneLoading = std::shared_future<std::shared_ptr<const WheelScene>>;

/// WheelScene(scene_file) read in the background at a low priority while the run starts.
WheelSceneLoading loadWheelSceneInBackground(const std::string& scene_file);

/// WheelScene of a copy of `description` (a scene file this process has read already), made in
/// the background as loadWheelSceneInBackground makes it.
WheelSceneLoading wheelSceneInBackground(std::shared_ptr<const scene::SceneDescription> description);

/// The check of `wheels` against the loaded scene (waits for it). Nothing, with a warning, if
/// the scene could not be read here or places no robot.
std::optional<WheelsOverScene> wheelCheckOnScene(const WheelSceneLoading& scene, const std::vector<WheelMount>& wheels);

/// The static surface of `scene` in the wall frame of its robot's 3d Pose element, reaching as
/// deep as the depth camera (coverageReach), enveloped over a tyre patch of `patch_m`
/// (DriveParams::tyre_patch_m; 0: as sampled).
scene::SurfaceHeights surfaceUnderWheels(const WheelScene& scene, double patch_m = 0.0);

/// What the drive's wheels stand on (DriveParams::ground): surfaceUnderWheels of the loading
/// scene, made in the background at a low priority while the run starts. A scene that could not
/// be read comes out of the first wheel query as a ConfigError naming the scene file (the
/// wheels never fall back to the plane unasked).
std::shared_ptr<const WheelGround> wheelGroundOfScene(const WheelSceneLoading& scene, double patch_m = 0.0);

}  // namespace climbsim::drive
