#pragma once
/// @file
/// The scene of one run: a scenario that changes the generated pylon (Scenario::crack) runs on
/// a pylon generated for it into RUN_DIR/scene/ (writePylonScene with the build's seed), so
/// that a sweep over the crack's depth or width needs no rebuild and every variant keeps the
/// scene it ran on. The launcher (`climbsim run|up`) and climbsim-solo both prepare a run
/// directory through runScenarioText, so both runs read the same bytes.

#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/scenario.hpp"

namespace climbsim::surface {

/// The seed of the build's pylon (`climbsim-surface pylon` without --seed, CMake's
/// $BUILD/scenes/pylon.xml): a run's own pylon differs from it in the crack only.
inline constexpr std::uint64_t kPylonSeed = 1;

/// Generates the pylon of `scenario` into `run_dir`/scene when it sets a crack and returns its
/// pylon.xml (absolute); "" when the scenario runs on its scene file as it is. Deterministic:
/// the same crack gives the same bytes. ConfigError if the directory cannot be written.
std::string generateRunScene(const Scenario& scenario, const std::string& run_dir);

/// resolvedScenarioText of `path` with `overrides` for a run in `run_dir`, after generating
/// the run's scene (generateRunScene) when the scenario needs one: the text to write to
/// RUN_DIR/scenario.yaml. Validates like loadScenario (ConfigError before anything is written).
std::string runScenarioText(const std::string& path, const std::vector<std::string>& overrides,
                            const std::string& build_dir, const std::string& run_dir);

}  // namespace climbsim::surface
