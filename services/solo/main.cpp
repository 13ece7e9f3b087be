/// climbsim-solo SCENARIO --out DIR [--set KEY=VALUE ...]: the in-process reference run
/// (runner/solo_run.hpp). Every model of the default composition in this one process, on one
/// thread, without DDS; writes the run directory `climbsim run` writes (scenario.yaml,
/// trace.csv, summary.json, pictures/, plots/) with the same trace.csv. Exit code as `run`:
/// 0 completed, 5 fell, 4 stopped (SIGINT/SIGTERM: stops after the step under way), 1 failed
/// (end_on.seal_over_nothing), 2 bad input. A run that completed but slid beyond the scenario's
/// slide_limit_m says so on its last line (exit code 0: the run itself completed).

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/run_summary/run_summary.hpp"
#include "plot/run_plots.hpp"
#include "runner/solo_run.hpp"

#ifndef CLIMBSIM_ROOT
#error "CLIMBSIM_ROOT must name the repository (deploy/scenarios)"
#endif
#ifndef CLIMBSIM_BUILD_DIR
#error "CLIMBSIM_BUILD_DIR must name the build directory (a scenario's $BUILD/)"
#endif

namespace {
std::atomic<bool> g_stop{false};
extern "C" void onSignal(int) { g_stop.store(true); }
}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-solo: every model of the default composition in one process, no DDS"};
  solo::SoloOptions options;
  std::string scenario;
  bool no_plots = false;
  app.add_option("SCENARIO", scenario, "scenario file or name in deploy/scenarios")->required();
  app.add_option("--out", options.out_dir, "run directory: scenario.yaml, trace.csv, summary.json, pictures, plots")
      ->required();
  app.add_option("--set", options.overrides, "override a scenario key: --set duration_s=5 (repeatable)");
  app.add_flag("--no-plots", no_plots, "do not draw plots/*.png (sweeps draw their own)");
  bool no_mcap = false;
  app.add_flag("--no-mcap", no_mcap, "write no run.mcap (docs/recordings.md)");
  return guardedMain(app, argc, argv, "solo", [&]() -> int {
    namespace fs = std::filesystem;
    options.scenario_file = scenario.find('/') != std::string::npos || fs::path(scenario).extension() == ".yaml"
                                ? scenario
                                : std::string(CLIMBSIM_ROOT) + "/deploy/scenarios/" + scenario + ".yaml";
    if (!fs::exists(options.scenario_file)) {
      throw ConfigError("SCENARIO = " + scenario + ": no such file (" + options.scenario_file + ")");
    }
    options.build_dir = CLIMBSIM_BUILD_DIR;
    options.mcap = !no_mcap;
    options.stop = &g_stop;
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const solo::SoloResult result = solo::runSolo(options);
    if (!no_plots && result.steps > 0) {
      try {
        const auto written = plot::writeRunPlots(options.out_dir, (fs::path(options.out_dir) / "plots").string());
        spdlog::info("solo: {} plots in {}/plots", written.size(), options.out_dir);
      } catch (const std::exception& e) {
        spdlog::warn("solo: the plots failed: {}", e.what());  // a plot failure is not the run's
      }
    }
    if (result.outcome == "fell" || result.outcome == "failed") {
      spdlog::error("{} (exit code {})", result.reason, result.exit_code);
    } else if (const auto slid = run_summary::slideBeyondLimitOf(options.out_dir); !slid.empty()) {
      spdlog::warn("solo: {}, but {}", result.outcome, slid);
    }
    return result.exit_code;
  });
}
