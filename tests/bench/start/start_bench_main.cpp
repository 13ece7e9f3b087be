/// climbsim-bench-start: what a run costs besides its steps, the price a sweep pays for every
/// variant. In each of --rounds rounds, alternating which goes first, a distributed run (the
/// launcher with deploy/compose.yaml: every service a process on Fast DDS) and a solo run
/// (climbsim-solo: one process, no DDS) of the scenario (default crack-descent) for --steps
/// steps, plots included. Prints each round and the medians:
///
///   bench: start: round K: distributed_s=.. distributed_cpu_s=.. solo_s=.. solo_cpu_s=..
///   bench: start: scenario=.. steps=.. distributed_s=.. distributed_cpu_s=.. solo_s=.. solo_cpu_s=..
///                 distributed_over_solo=.. (reference: solo_s=..)
///
/// `*_s`: wall seconds from starting the program to its exit; `*_cpu_s`: user + system CPU of it
/// and every process it started (wait4's rusage, which holds the children it waited for).
/// Writes the same as JSON to --out.

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/main_guard.hpp"
#include "climbsim/process.hpp"

namespace {

namespace fs = std::filesystem;

struct Cost {
  double wall_s = 0, cpu_s = 0;
};

/// Runs `argv` to its end (output to `log`); throws naming the log if it fails.
Cost timed(const std::vector<std::string>& argv, const std::string& log) {
  climbsim::ProcessSpec spec;
  spec.argv = argv;
  spec.output_file = log;
  fs::remove(log);
  const auto start = std::chrono::steady_clock::now();
  climbsim::ChildProcess child(spec);
  const auto code = child.waitFor(std::chrono::minutes(5));
  Cost cost;
  cost.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!code || *code != 0) {
    child.signal(SIGKILL);
    throw std::runtime_error(argv[0] + " failed (exit " + (code ? std::to_string(*code) : "none: killed") +
                             "); see " + log);
  }
  cost.cpu_s = child.cpuSeconds().value_or(0.0);
  return cost;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-start: the wall and CPU time of a run besides its steps, distributed and solo"};
  std::string out_file, root = CLIMBSIM_ROOT, build = CLIMBSIM_BUILD_DIR, scenario = "crack-descent";
  int rounds = 5, steps = 10;
  double step_s = 0.005;
  app.add_option("--out", out_file, "JSON file to write");
  app.add_option("--root", root, "the climbsim checkout");
  app.add_option("--build", build, "the build directory");
  app.add_option("--scenario", scenario, "scenario name or file");
  app.add_option("--rounds", rounds, "rounds of one distributed and one solo run (medians)")->check(CLI::Range(1, 100));
  app.add_option("--steps", steps, "steps of each run")->check(CLI::Range(1, 100000));
  app.add_option("--step-s", step_s, "the scenario's step [s] (duration = steps x step)")->check(CLI::PositiveNumber);
  return climbsim::guardedMain(app, argc, argv, "bench-start", [&] {
    const fs::path dir = fs::path(build) / "bench" / "start";
    fs::create_directories(dir);
    char duration[64];
    std::snprintf(duration, sizeof duration, "duration_s=%.9g", steps * step_s);
    const std::vector<std::string> distributed = {build + "/bin/climbsim-compose", "--root", root, "--build", build,
                                                  "run", scenario, "--set", duration, "--name", "bench-start",
                                                  "--out", (dir / "distributed").string()};
    const std::vector<std::string> solo = {build + "/bin/climbsim-solo", scenario, "--set", duration, "--out",
                                           (dir / "solo").string()};
    std::vector<double> d_wall, d_cpu, s_wall, s_cpu;
    for (int round = 1; round <= rounds; ++round) {
      Cost d, s;
      if (round % 2) {
        d = timed(distributed, (dir / "distributed.log").string());
        s = timed(solo, (dir / "solo.log").string());
      } else {
        s = timed(solo, (dir / "solo.log").string());
        d = timed(distributed, (dir / "distributed.log").string());
      }
      std::printf("bench: start: round %d: distributed_s=%.3f distributed_cpu_s=%.3f solo_s=%.3f solo_cpu_s=%.3f\n",
                  round, d.wall_s, d.cpu_s, s.wall_s, s.cpu_s);
      d_wall.push_back(d.wall_s);
      d_cpu.push_back(d.cpu_s);
      s_wall.push_back(s.wall_s);
      s_cpu.push_back(s.cpu_s);
    }
    const double dw = median(d_wall), dc = median(d_cpu), sw = median(s_wall), sc = median(s_cpu);
    std::printf("bench: start: scenario=%s steps=%d distributed_s=%.3f distributed_cpu_s=%.3f solo_s=%.3f "
                "solo_cpu_s=%.3f distributed_over_solo=%.2f (reference: solo_s=%.3f)\n",
                scenario.c_str(), steps, dw, dc, sw, sc, dw / sw, sw);
    if (!out_file.empty()) {
      std::ofstream(out_file) << nlohmann::json{{"scenario", scenario},
                                                {"steps", steps},
                                                {"rounds", rounds},
                                                {"distributed_s", dw},
                                                {"distributed_cpu_s", dc},
                                                {"solo_s", sw},
                                                {"solo_cpu_s", sc},
                                                {"distributed_over_solo", dw / sw}}
                                         .dump(2)
                              << "\n";
    }
    return 0;
  });
}
