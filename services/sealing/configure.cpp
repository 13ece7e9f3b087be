#include "configure.hpp"

#include "climbsim/errors.hpp"
#include "climbsim/robot/depth_view.hpp"

namespace climbsim::sealing {
namespace {
/// --view-m, else the robot's view [m].
double viewOf(const RobotGeometry& geometry, const SealingOverrides& overrides) {
  const double view_m = overrides.view_m ? *overrides.view_m : robotDepthViewM(geometry);
  if (!(view_m > 0.0)) throw ConfigError("--view-m = " + std::to_string(view_m) + ": must be > 0");
  return view_m;
}
}  // namespace

PixelGrid sealingCamera(const ScenarioAndRobot& run, const SealingOverrides& overrides) {
  int px = kDefaultCameraPx;
  if (run.scenario && run.scenario->depth_camera.size_px > 0) px = run.scenario->depth_camera.size_px;
  if (overrides.camera_px) px = *overrides.camera_px;
  return PixelGrid{px, px, viewOf(run.geometry, overrides) / px};
}

SealingSetup configureSealing(const ScenarioAndRobot& run, const SealingOverrides& overrides) {
  SealingSetup setup;
  const Scenario* scenario = run.scenario ? &*run.scenario : nullptr;
  setup.camera = sealingCamera(run, overrides);
  setup.view_m = viewOf(run.geometry, overrides);
  setup.shard = ShardSpec::parse(overrides.shard);
  setup.params = sealingParamsFromRobot(run.robot, run.geometry);
  if (scenario != nullptr) {
    if (scenario->depth_camera.subpixel) setup.params.strip_outline = StripOutline::kSubpixelShares;
    if (setup.shard.index == 0) setup.picture_times = scenario->pictures.sealing_at_s;
    setup.end_on_seal_over_nothing = scenario->end_on.seal_over_nothing;
  }
  return setup;
}

}  // namespace climbsim::sealing
