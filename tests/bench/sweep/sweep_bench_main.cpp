/// climbsim-bench-sweep: what a Ray cluster costs a sweep. The same sweep (--variants set-points
/// of crack-descent, --duration s each, solo) runs on this machine with `-j 2` and through a Ray
/// head on this machine with 2 CPUs (`deploy/climbsim cluster up --cpus 2`), in one run. Prints
///
///   bench: sweep: variants=.. local_per_min=.. ray_per_min=.. ray_over_local=.. ray_task_overhead_s=..
///          target=0.9 met=true|false
///
/// and writes the same as JSON to --out. ray_over_local = ray_per_min / local_per_min;
/// ray_task_overhead_s: the wall time a Ray task adds to its variant, (2 x sweep wall - the sum of
/// the variants' own wall_s) / variants, Ray's minus the local sweep's (both keep 2 at a time).

#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"

namespace {

struct SweepTime {
  double wall_s = 0.0;      ///< the whole sweep
  double variants_s = 0.0;  ///< sum of the variants' wall_s (sweep.csv)
};

/// Sum of the wall_s column of a sweep.csv.
double variantSeconds(const std::string& csv_file) {
  std::ifstream in(csv_file);
  std::string header;
  std::getline(in, header);
  std::size_t column = 0;
  for (std::size_t at = 0, i = 0;; ++i) {
    const auto comma = header.find(',', at);
    if (header.substr(at, comma - at) == "wall_s") {
      column = i;
      break;
    }
    if (comma == std::string::npos) throw std::runtime_error(csv_file + ": no wall_s column");
    at = comma + 1;
  }
  double sum = 0.0;
  for (std::string line; std::getline(in, line);) {
    std::size_t at = 0;
    for (std::size_t i = 0; i < column; ++i) at = line.find(',', at) + 1;
    sum += std::strtod(line.c_str() + at, nullptr);
  }
  return sum;
}

SweepTime timedSweep(const std::string& args, const std::string& out) {
  const std::string command = std::string(CLIMBSIM_BUILD_DIR) + "/bin/climbsim-sweep " + args + " --out " + out +
                              " > " + out + ".log 2>&1";
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(command.c_str());
  SweepTime t;
  t.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error(command + " failed; see " + out + ".log");
  t.variants_s = variantSeconds(out + "/sweep.csv");
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-sweep: a sweep with -j 2 here and through a local Ray head with 2 CPUs"};
  std::string out_file;
  int variants = 8;
  double duration_s = 4.0;
  int port = 6591;
  app.add_option("--out", out_file, "JSON file to write");
  app.add_option("--variants", variants, "variants of the sweep")->check(CLI::Range(2, 100));
  app.add_option("--duration", duration_s, "simulated seconds of each variant")->check(CLI::Range(0.5, 60.0));
  app.add_option("--port", port, "port of the Ray head this benchmark starts and stops");
  return climbsim::guardedMain(app, argc, argv, "bench-sweep", [&] {
    std::string values;
    for (int i = 0; i < variants; ++i) values += (i ? "," : "") + std::to_string(700 + 100 * i);
    char duration[32];
    std::snprintf(duration, sizeof duration, "%g", duration_s);
    const std::string sweep = "crack-descent --set duration_s=" + std::string(duration) +
                              " --set controller.downforce_n=" + values;
    const std::string runs = std::string(CLIMBSIM_BUILD_DIR) + "/bench/sweep-runs";
    std::filesystem::create_directories(runs);
    const std::string cluster = "CLIMBSIM_BUILD_DIR=" CLIMBSIM_BUILD_DIR " " CLIMBSIM_ROOT "/deploy/climbsim cluster ";
    const std::string port_option = " --port " + std::to_string(port);
    const SweepTime local = timedSweep(sweep + " -j 2", runs + "/local");
    if (std::system((cluster + "up --cpus 2" + port_option + " > " + runs + "/cluster.log 2>&1").c_str()) != 0) {
      throw std::runtime_error("`deploy/climbsim cluster up` failed; see " + runs + "/cluster.log");
    }
    std::ifstream address_file(std::string(CLIMBSIM_BUILD_DIR) + "/ray/" + std::to_string(port) + "/address");
    std::string address;
    address_file >> address;
    SweepTime ray;
    try {
      ray = timedSweep(sweep + " --ray " + address, runs + "/ray");
    } catch (...) {
      std::system((cluster + "down" + port_option + " > /dev/null 2>&1").c_str());
      throw;
    }
    std::system((cluster + "down" + port_option + " > /dev/null 2>&1").c_str());
    const double local_per_min = 60.0 * variants / local.wall_s;
    const double ray_per_min = 60.0 * variants / ray.wall_s;
    const double ratio = ray_per_min / local_per_min;
    const double overhead_s =
        ((2.0 * ray.wall_s - ray.variants_s) - (2.0 * local.wall_s - local.variants_s)) / variants;
    constexpr double kTarget = 0.9;
    std::printf("bench: sweep: variants=%d local_per_min=%.1f ray_per_min=%.1f ray_over_local=%.3f "
                "ray_task_overhead_s=%.2f local_wall_s=%.1f ray_wall_s=%.1f target=%.1f met=%s\n",
                variants, local_per_min, ray_per_min, ratio, overhead_s, local.wall_s, ray.wall_s, kTarget,
                ratio >= kTarget ? "true" : "false");
    if (!out_file.empty()) {
      std::ofstream(out_file) << nlohmann::json{{"variants", variants},          {"duration_s", duration_s},
                                                {"local_per_min", local_per_min}, {"ray_per_min", ray_per_min},
                                                {"ray_over_local", ratio},        {"ray_task_overhead_s", overhead_s},
                                                {"local_wall_s", local.wall_s},   {"ray_wall_s", ray.wall_s},
                                                {"target", kTarget},              {"met", ratio >= kTarget}}
                                         .dump(2)
                              << "\n";
    }
    return 0;
  });
}
