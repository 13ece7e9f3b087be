#include "configure.hpp"

#include <cmath>
#include <utility>

#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"
#include "wheels_over_scene.hpp"

namespace climbsim::drive {
namespace {

WallOrientation wallOf(const Scenario::Wall& wall) {
  switch (wall.kind) {
    case Scenario::WallKind::kFloor: return WallOrientation::floor();
    case Scenario::WallKind::kOverhang: return WallOrientation::overhang(wall.overhang_deg);
    case Scenario::WallKind::kVertical: break;
  }
  return WallOrientation::vertical();
}

void requireFinite(const char* option, double value) {
  if (!std::isfinite(value)) throw ConfigError(std::string(option) + " = " + std::to_string(value) + ": must be finite");
}

}  // namespace

DriveSetup configureDrive(const ScenarioAndRobot& run, const DriveOverrides& overrides, const std::string& build_dir) {
  DriveSetup setup;
  setup.inputs = parseDriveNodeInputs(overrides.inputs);
  setup.wall = overrides.wall ? WallOrientation::parse("--wall", *overrides.wall) : WallOrientation::vertical();
  double x_m = overrides.x_m.value_or(0.0), y_m = overrides.y_m.value_or(0.0), yaw_deg = overrides.yaw_deg.value_or(0.0);
  double hold_s = overrides.hold_s.value_or(0.0);
  std::optional<double> substep_hz = overrides.substep_hz;
  if (const auto& scenario = run.scenario) {
    x_m = scenario->start.x_m;
    y_m = scenario->start.y_m;
    yaw_deg = scenario->start.yaw_deg;
    setup.wall = wallOf(scenario->wall);
    substep_hz = scenario->rates.drive_hz;
    hold_s = scenario->start.hold_s;
    setup.end_on_fall = scenario->end_on.fall;
    setup.scene_file = scenario->scenePath(build_dir);
    if (overrides.scene_read && !setup.scene_file.empty() && overrides.scene_read->file == setup.scene_file) {
      setup.wheel_scene = wheelSceneInBackground(overrides.scene_read);
    } else if (!setup.scene_file.empty()) {
      setup.wheel_scene = loadWheelSceneInBackground(setup.scene_file);
    }
  }
  if (substep_hz && !(std::isfinite(*substep_hz) && *substep_hz >= 100.0 && *substep_hz <= 100000.0)) {
    throw ConfigError("--substep-hz = " + std::to_string(*substep_hz) + ": must be in [100, 100000]");
  }
  requireFinite("--x-m", x_m);
  requireFinite("--y-m", y_m);
  requireFinite("--yaw-deg", yaw_deg);
  setup.params = driveParamsFromRobot(run.robot, run.geometry);
  if (substep_hz) setup.params.substep_s = 1.0 / *substep_hz;
  if (overrides.contact) setup.params.contact_backend = parseContactBackend("--contact", *overrides.contact);
  // wall.wheels_on: surface puts the wheels on the scene's surface. Only the direct backend
  // has the surface; the simbody one keeps the plane, so asking for both is refused.
  if (run.scenario && run.scenario->wall.wheels_on == Scenario::WheelsOn::kSurface && !setup.scene_file.empty()) {
    if (setup.params.contact_backend != ContactBackend::kDirect) {
      throw ConfigError(run.scenario->source + ": wall.wheels_on = surface: the simbody contact backend (--contact "
                        "simbody) puts the wheels on the wall plane; set wall.wheels_on: plane for it");
    }
    setup.params.ground = wheelGroundOfScene(setup.wheel_scene, setup.params.tyre_patch_m);
  }
  // With thermo's AdhesionForce as an input, its initial state (ambient chambers, F = 0)
  // holds until its first sample; without it, the desired downforce for the whole run.
  setup.downforce_n = overrides.downforce_n.value_or(setup.inputs.adhesion ? kAdhesionForceBeforeThermo_n
                                                                            : run.robot.adhesion.desired_downforce_n);
  setup.start = StartPose{x_m, y_m, yaw_deg * 3.14159265358979323846 / 180.0};
  if (!(std::isfinite(hold_s) && hold_s >= 0.0)) {
    throw ConfigError("--hold-s = " + std::to_string(hold_s) + ": must be finite and >= 0");
  }
  setup.hold_until_ns = std::llround(hold_s * 1e9);
  return setup;
}

}  // namespace climbsim::drive
