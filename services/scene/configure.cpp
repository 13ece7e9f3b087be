#include "configure.hpp"

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"

#ifndef CLIMBSIM_DEFAULT_SCENE_FILE
#error "CLIMBSIM_DEFAULT_SCENE_FILE must name the default scene (generated at build time)"
#endif

namespace climbsim::scene {
namespace {

struct Outputs {
  bool depth = false, laser = false;
};

Outputs outputsOf(const std::string& list) {
  Outputs out;
  for (const auto& output : parseNameList("--outputs", list)) {
    if (output == "depth") {
      out.depth = true;
    } else if (output == "laser") {
      out.laser = true;
    } else {
      throw ConfigError("--outputs: unknown output '" + output + "' (expected depth, laser)");
    }
  }
  return out;
}

}  // namespace

SceneParams sceneParams(const Scenario* scenario, const SceneOverrides& overrides) {
  SceneParams params;
  if (overrides.pose_element) params.pose_element = *overrides.pose_element;
  if (overrides.camera) params.camera = *overrides.camera;
  if (overrides.laser) params.laser = *overrides.laser;
  if (scenario != nullptr && scenario->depth_camera.size_px > 0) params.depth_size_px = scenario->depth_camera.size_px;
  if (overrides.depth_size_px) params.depth_size_px = overrides.depth_size_px;
  if (overrides.depth_width_m) params.depth_width_m = overrides.depth_width_m;
  if (overrides.near_m) params.near_m = overrides.near_m;
  if (overrides.far_m) params.far_m = overrides.far_m;
  params.quantise_8bit = overrides.quantise_8bit;
  if (overrides.backend == "embree") {
    params.backend = DepthBackend::kEmbree;
  } else if (overrides.backend != "rasterizer") {
    throw ConfigError("--depth-backend = '" + overrides.backend + "': expected rasterizer or embree");
  }
  if (!outputsOf(overrides.outputs).laser) params.laser.clear();
  return params;
}

SceneSetup configureScene(const Scenario* scenario, const SceneOverrides& overrides, const std::string& build_dir) {
  SceneSetup setup;
  setup.scene_file = overrides.scene_file.value_or(CLIMBSIM_DEFAULT_SCENE_FILE);
  if (scenario != nullptr) {
    setup.scene_file = scenario->scenePath(build_dir);
    setup.robot_file = scenario->robotPath();
  }
  setup.params = sceneParams(scenario, overrides);
  const Outputs outputs = outputsOf(overrides.outputs);
  setup.write_depth = outputs.depth;
  setup.write_laser = outputs.laser;
  return setup;
}

}  // namespace climbsim::scene
