/// climbsim-plot RUN_DIR [--out DIR]: the plots of a finished run (plot/run_plots.hpp) as PNG
/// files in RUN_DIR/plots/ (or DIR): downforce.png, pressures.png, valves.png, wheel_loads.png
/// and ring_<t>s.png for each t of the scenario's pictures.ring_at_s. Bad input (missing
/// trace.csv or scenario.yaml, a missing column, a cell that is not a number) is one line naming
/// the file, line/column and value, and exit code 2.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "plot/run_plots.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-plot: PNG plots of a finished run directory"};
  std::string run_dir;
  std::string out_dir;
  app.add_option("RUN_DIR", run_dir, "run directory (trace.csv, scenario.yaml) written by `climbsim run`")
      ->required();
  app.add_option("--out", out_dir, "directory for the PNG files (default: RUN_DIR/plots)");
  return guardedMain(app, argc, argv, "plot", [&]() -> int {
    if (!std::filesystem::is_directory(run_dir)) throw ConfigError(run_dir + ": not a run directory");
    if (out_dir.empty()) out_dir = (std::filesystem::path(run_dir) / "plots").string();
    const auto written = plot::writeRunPlots(run_dir, out_dir);
    spdlog::info("plot: {} PNG files in {}", written.size(), out_dir);
    return kExitOk;
  });
}
