#pragma once
/// @file
/// climbsim-drive's configuration (docs/design.md#configuration): the run's scenario, the robot
/// and the command line's own options to the drive model's parameters, the wall, the start
/// pose and what the node needs. climbsim-drive's main and climbsim solo both call
/// configureDrive; every default is the model's (DriveParams, WallOrientation, StartPose) or
/// this file's.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "climbsim/scenario_and_robot.hpp"
#include "drive_params.hpp"
#include "node/drive_node.hpp"
#include "node/wheels_over_scene.hpp"

namespace climbsim::drive {

/// climbsim-drive's options besides --scenario/--set/--robot. Those a scenario sets (x, y,
/// yaw, wall, substep rate, hold) are refused with --scenario by the command line.
struct DriveOverrides {
  std::optional<double> x_m;                ///< --x-m: start x in W [m] (default 0)
  std::optional<double> y_m;                ///< --y-m: start y in W [m] (default 0)
  std::optional<double> yaw_deg;            ///< --yaw-deg: start heading [deg] (default 0)
  std::optional<std::string> wall;          ///< --wall: WallOrientation::parse (default vertical)
  std::optional<double> substep_hz;         ///< --substep-hz [Hz], 100..100000 (default: DriveParams)
  std::optional<double> hold_s;             ///< --hold-s: held at the start pose until then [s] (default 0)
  /// --downforce [N]: the adhesion force until thermo's first AdhesionForce (default
  /// kAdhesionForceBeforeThermo_n), or for the whole run without that input (default: the
  /// robot's adhesion.desired_downforce_n).
  std::optional<double> downforce_n;
  std::string inputs = "command,adhesion";  ///< --inputs: parseDriveNodeInputs
  std::optional<std::string> contact;       ///< --contact: parseContactBackend (default: DriveParams)
  /// The scenario's scene file as this process read it already (the in-process runner, which
  /// renders it too): the wheels' scene is made of a copy instead of reading the file again.
  /// Used only when its `file` is the scenario's scene path.
  std::shared_ptr<const scene::SceneDescription> scene_read;
};

/// Everything climbsim-drive's node is made of.
struct DriveSetup {
  DriveParams params;              ///< of the robot; substep and force backend set
  WallOrientation wall;            ///< gravity
  StartPose start;                 ///< yaw in rad
  std::int64_t hold_until_ns = 0;  ///< DriveNode::holdUntil [ns]
  double downforce_n = 0.0;        ///< DriveNode's adhesion force before (or without) AdhesionForce [N]
  DriveNodeInputs inputs;          ///< the topics read
  bool end_on_fall = false;        ///< the scenario's end_on.fall; without a scenario a fall never ends the run
  std::string scene_file;          ///< the scenario's scene (the wheel check); "" without a scenario
  /// scene_file read once in the background (loadWheelSceneInBackground) for the wheel check and
  /// the surface under the wheels; not valid() without a scene.
  WheelSceneLoading wheel_scene;
};

/// The drive's setup from `run` (the scenario's start, wall, rates.drive_hz, start.hold_s,
/// end_on.fall and scene, resolved against `build_dir`) and `overrides`. With a scene and the
/// wall.wheels_on: surface the wheels stand on the scene's surface (params.ground:
/// wheelGroundOfScene, loading in the background until the model's first step needs it; the
/// simbody backend refuses it). ConfigError naming the
/// option and value: --substep-hz outside [100, 100000], a start not finite, --hold-s < 0, a
/// bad --wall, --contact, --inputs or --downforce, bad robot parameters.
DriveSetup configureDrive(const ScenarioAndRobot& run, const DriveOverrides& overrides, const std::string& build_dir);

}  // namespace climbsim::drive
