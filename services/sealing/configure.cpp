#include "configure.hpp"

#include "climbsim/errors.hpp"

namespace climbsim::sealing {
namespace {
/// --view-m, else kDefaultViewM [m].
double viewOf(const SealingOverrides& overrides) {
  const double view_m = overrides.view_m.value_or(kDefaultViewM);
  if (!(view_m > 0.0)) throw ConfigError("--view-m = " + std::to_string(view_m) + ": must be > 0");
  return view_m;
}
}  // namespace

PixelGrid sealingCamera(const Scenario* scenario, const SealingOverrides& overrides) {
  int px = kDefaultCameraPx;
  if (scenario != nullptr && scenario->depth_camera.size_px > 0) px = scenario->depth_camera.size_px;
  if (overrides.camera_px) px = *overrides.camera_px;
  return PixelGrid{px, px, viewOf(overrides) / px};
}

SealingSetup configureSealing(const ScenarioAndRobot& run, const SealingOverrides& overrides) {
  SealingSetup setup;
  const Scenario* scenario = run.scenario ? &*run.scenario : nullptr;
  setup.camera = sealingCamera(scenario, overrides);
  setup.view_m = viewOf(overrides);
  setup.shard = ShardSpec::parse(overrides.shard);
  setup.params = sealingParamsFromRobot(run.robot, run.geometry);
  if (scenario != nullptr) {
    if (setup.shard.index == 0) setup.picture_times = scenario->pictures.sealing_at_s;
    setup.end_on_seal_over_nothing = scenario->end_on.seal_over_nothing;
  }
  return setup;
}

}  // namespace climbsim::sealing
