#include "climbsim/run_prep/run_scene.hpp"

#include <filesystem>

#include <spdlog/spdlog.h>

#include "climbsim/wall_patches/pylon_scene.hpp"

namespace climbsim::surface {

std::string generateRunScene(const Scenario& scenario, const std::string& run_dir) {
  if (!scenario.crack) return "";
  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(fs::path(run_dir) / "scene").lexically_normal();
  // A scene an earlier run left here may have had another crack or more files.
  std::error_code error;
  fs::remove_all(dir, error);
  PylonCrack crack;
  crack.depth_m = scenario.crack->depth_m;
  crack.width_m = scenario.crack->width_m;
  spdlog::info("scene: generating the pylon with a crack {} mm deep, {} mm wide into {}", crack.depth_m * 1e3,
               crack.width_m * 1e3, dir.string());
  writePylonScene(dir.string(), kPylonSeed, crack);
  return (dir / "pylon.xml").string();
}

std::string runScenarioText(const std::string& path, const std::vector<std::string>& overrides,
                            const std::string& build_dir, const std::string& run_dir) {
  const Scenario scenario = loadScenario(path, overrides);
  return resolvedScenarioText(path, overrides, build_dir, generateRunScene(scenario, run_dir));
}

}  // namespace climbsim::surface
