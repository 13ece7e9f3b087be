#include "configure.hpp"

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"
#include "climbsim/robot/depth_view.hpp"
#include "climbsim/wall/robot_body_part.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "climbsim/wall_patches/robot_body.hpp"

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

bool subpixelLeakage(const ScenarioAndRobot& run) { return run.scenario && run.scenario->depth_camera.subpixel; }

SceneParams sceneParams(const ScenarioAndRobot& run, const SceneOverrides& overrides) {
  const Scenario* scenario = run.scenario ? &*run.scenario : nullptr;
  SceneParams params;
  params.robot_view_m = robotDepthViewM(run.geometry);
  if (overrides.pose_element) params.pose_element = *overrides.pose_element;
  if (overrides.camera) params.camera = *overrides.camera;
  if (overrides.laser) params.laser = *overrides.laser;
  if (scenario != nullptr && scenario->depth_camera.size_px > 0) params.depth_size_px = scenario->depth_camera.size_px;
  if (overrides.depth_size_px) params.depth_size_px = overrides.depth_size_px;
  if (overrides.depth_width_m) params.depth_width_m = overrides.depth_width_m;
  if (overrides.near_m) params.near_m = overrides.near_m;
  if (overrides.far_m) params.far_m = overrides.far_m;
  params.quantise_8bit = overrides.quantise_8bit;
  if (subpixelLeakage(run)) {
    params.depth_samples_per_pixel = kSubpixelDepthSamplesPerPixel;
    params.depth_support_slope = run.robot.sealing.max_slope;
  }
  if (overrides.backend == "embree") {
    params.backend = DepthBackend::kEmbree;
  } else if (overrides.backend != "rasterizer") {
    throw ConfigError("--depth-backend = '" + overrides.backend + "': expected rasterizer or embree");
  }
  if (!outputsOf(overrides.outputs).laser) params.laser.clear();
  return params;
}

SceneSetup configureScene(const ScenarioAndRobot& run, const SceneOverrides& overrides, const std::string& build_dir) {
  SceneSetup setup;
  setup.scene_file = overrides.scene_file.value_or(CLIMBSIM_DEFAULT_SCENE_FILE);
  if (run.scenario) {
    setup.scene_file = run.scenario->scenePath(build_dir);
    setup.robot_file = run.scenario->robotPath();
  }
  setup.params = sceneParams(run, overrides);
  setup.subpixel = subpixelLeakage(run);
  const surface::SurfaceMesh body = surface::robotBodyMesh(run.geometry);
  setup.robot_body.file = run.robot_file + " (body)";
  setup.robot_body.vertices_m = body.vertices_m;
  setup.robot_body.triangles = body.triangles;
  const Outputs outputs = outputsOf(overrides.outputs);
  setup.write_depth = outputs.depth;
  setup.write_laser = outputs.laser;
  if (run.scenario && setup.write_depth && setup.params.backend == DepthBackend::kRasterizer) {
    setup.frames.robot_file = setup.robot_file;
    setup.frames.subpixel = setup.subpixel;
    setup.frames.read_at_s = run.scenario->pictures.sealing_at_s;
    setup.frames.read_lag_ns = run.scenario->step_ns;
    setup.frames.every_frame_whole = run.scenario->recording.depth_images;
  }
  return setup;
}

Scene loadRunScene(const SceneSetup& setup) { return runSceneOf(loadSceneDescription(setup.scene_file), setup); }

Scene runSceneOf(SceneDescription description, const SceneSetup& setup) {
  attachRobotBody(description, setup.params.pose_element, setup.robot_body);
  return Scene(std::move(description));
}

}  // namespace climbsim::scene
