/// climbsim-plot-figure9 RUN_DIR [--out PNG] [--crack-y-m Y] [--from-s T]: the comparison of a run of the
/// figure9 scenario with the original system's figure 9 (plot/figure9_plot.hpp), written to
/// RUN_DIR/plots/figure9.png (or PNG). Bad input is one line naming the file, exit code 2.

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "plot/figure9_plot.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-plot-figure9: a run across the crack next to the original's figure 9"};
  std::string run_dir;
  std::string out;
  double crack_y_m = 0.70;
  double from_s = 2.0;
  app.add_option("RUN_DIR", run_dir, "run directory of the figure9 scenario")->required();
  app.add_option("--out", out, "PNG file (default: RUN_DIR/plots/figure9.png)");
  app.add_option("--crack-y-m", crack_y_m, "wall height of the horizontal crack [m] (default pylon: 0.70)");
  app.add_option("--from-s", from_s, "plot the rows from this time on [s] (default 2: after the figure9 scenario's hold)");
  return guardedMain(app, argc, argv, "plot", [&]() -> int {
    namespace fs = std::filesystem;
    if (!fs::is_directory(run_dir)) throw ConfigError(run_dir + ": not a run directory");
    if (out.empty()) out = (fs::path(run_dir) / "plots" / "figure9.png").string();
    if (fs::path(out).has_parent_path()) fs::create_directories(fs::path(out).parent_path());
    const auto trace = plot::TraceTable::read((fs::path(run_dir) / "trace.csv").string());
    if (!cv::imwrite(out, plot::figure9Plot(trace, crack_y_m, from_s))) throw ConfigError(out + ": cannot write the PNG");
    spdlog::info("plot: {}", out);
    return kExitOk;
  });
}
