#pragma once
/// @file
/// climbsim-sealing's configuration (docs/design.md#configuration): the run's scenario, the
/// robot and the command line's own options to the sealing model's parameters, its depth
/// camera, the shard and the pictures to keep. climbsim-sealing's main, climbsim solo and the
/// launcher's depth layout check all take the camera from here.

#include <optional>
#include <string>
#include <vector>

#include "climbsim/scenario_and_robot.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"
#include "node/sealing_node.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"

namespace climbsim::sealing {

/// climbsim-sealing's options besides --scenario/--set/--robot.
struct SealingOverrides {
  std::optional<int> camera_px;  ///< --camera-px: the image's side [px]
  std::optional<double> view_m;  ///< --view-m: the image's side on the wall [m]
  std::string shard = "0/1";     ///< --shard I/N: ShardSpec::parse
};

/// The depth image a shard of `run` reads: --camera-px, else the scenario's
/// depth_camera.size_px (when set, > 0), else kDefaultCameraPx pixels a side; pixel size
/// --view-m (else the robot's view, robotDepthViewM) divided by that. `run.scenario` may be
/// empty (a shard started without one). ConfigError "--view-m = V: must be > 0".
PixelGrid sealingCamera(const ScenarioAndRobot& run, const SealingOverrides& overrides);

/// Everything climbsim-sealing's model and node are made of.
struct SealingSetup {
  SealingParams params;                   ///< of the robot; strip_outline: depth_camera.subpixel
  PixelGrid camera;                       ///< sealingCamera
  double view_m = 0.0;                    ///< the image's side on the wall [m]
  ShardSpec shard;                        ///< this process's share of the segments
  /// When to keep pictures (the scenario's pictures.sealing_at_s) [s]: shard 0 keeps them (the
  /// other shards do not compute the pixels outside their region); none for the others.
  std::vector<double> picture_times;
  bool end_on_seal_over_nothing = false;  ///< the scenario's end_on.seal_over_nothing
};

/// The sealing setup of `run` and `overrides`. ConfigErrors as sealingCamera,
/// ShardSpec::parse and sealingParamsFromRobot give them.
SealingSetup configureSealing(const ScenarioAndRobot& run, const SealingOverrides& overrides = {});

}  // namespace climbsim::sealing
