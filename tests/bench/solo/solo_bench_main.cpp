/// climbsim-bench-solo: the speed limit of the closed loop. Every model of the default
/// composition in one process on one core, no DDS (climbsim-solo), on a scenario (default
/// crack-descent, its full duration). Prints
///
///   bench: solo: scenario=.. realtime_factor=.. sim_s=.. wall_s=.. steps=.. step_us=.. cpu_s=.. cores=1
///
/// and writes the same as JSON to --out. `bench: e2e:` measures the distributed run against it.

#include <cstdio>
#include <fstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/main_guard.hpp"
#include "solo_rtf.hpp"

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-solo: real-time factor of the in-process reference run on one core"};
  std::string out_file;
  std::string build = CLIMBSIM_BUILD_DIR;
  std::string scenario = "crack-descent";
  app.add_option("--out", out_file, "JSON file to write");
  app.add_option("--build", build, "the build directory");
  app.add_option("--scenario", scenario, "scenario name or file");
  return climbsim::guardedMain(app, argc, argv, "bench-solo", [&] {
    const auto cost = climbsim::bench::runSoloPinned(build, scenario, "solo-" + std::string("bench"));
    const double step_us = cost.steps > 0 ? 1e6 * cost.wall_s / cost.steps : 0.0;
    std::printf("bench: solo: scenario=%s realtime_factor=%.2f sim_s=%g wall_s=%.3f steps=%.0f step_us=%.1f "
                "cpu_s=%.2f cores=1 (core %d)\n",
                scenario.c_str(), cost.realtime_factor, cost.sim_s, cost.wall_s, cost.steps, step_us, cost.cpu_s,
                cost.core);
    if (!out_file.empty()) {
      std::ofstream(out_file) << nlohmann::json{{"scenario", scenario},     {"realtime_factor", cost.realtime_factor},
                                                {"sim_s", cost.sim_s},       {"wall_s", cost.wall_s},
                                                {"steps", cost.steps},       {"step_us", step_us},
                                                {"cpu_s", cost.cpu_s},       {"cores", 1}}
                                         .dump(2)
                              << "\n";
    }
    return 0;
  });
}
