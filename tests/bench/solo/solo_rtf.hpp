#pragma once
/// @file
/// The in-process reference run as a benchmark (docs/design.md#processes): climbsim-solo on a
/// scenario, pinned to one core, and its real-time factor (summary.json: simulated time over the
/// wall time of the stepping, scene and model loading left out, as the recorder's). Shared by
/// `bench: solo:` and `bench: e2e:` (distributed_over_solo, measured in the same run).

#include <sched.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "climbsim/process.hpp"

namespace climbsim::bench {

/// What one solo run cost.
struct SoloCost {
  double realtime_factor = 0.0;
  double sim_s = 0.0;
  double wall_s = 0.0;   ///< stepping only [s]
  double steps = 0.0;
  double cpu_s = 0.0;    ///< user + system CPU of the process [s], loading included
  int core = -1;         ///< the core it was pinned to
};

/// Runs `<build>/bin/climbsim-solo SCENARIO --out <build>/bench/<label> --no-plots [--set KEY=VALUE]...`
/// (one --set per entry of `overrides`) pinned to the first core this process may use.
/// std::runtime_error if it does not complete.
inline SoloCost runSoloPinned(const std::string& build, const std::string& scenario, const std::string& label,
                              const std::vector<std::string>& overrides = {}) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(build) / "bench" / label;
  fs::remove_all(dir);
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) throw std::runtime_error("sched_getaffinity failed");
  int core = 0;
  while (core < CPU_SETSIZE && !CPU_ISSET(core, &allowed)) ++core;
  // The child inherits the affinity of this process at fork: pin, start, restore.
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(core, &one);
  if (sched_setaffinity(0, sizeof(one), &one) != 0) throw std::runtime_error("sched_setaffinity failed");
  ProcessSpec spec;
  spec.argv = {build + "/bin/climbsim-solo", scenario, "--out", dir.string(), "--no-plots"};
  for (const std::string& o : overrides) {
    spec.argv.push_back("--set");
    spec.argv.push_back(o);
  }
  spec.output_file = dir.string() + ".log";
  fs::remove(spec.output_file);
  std::optional<ChildProcess> child;
  try {
    child.emplace(spec);
  } catch (...) {
    sched_setaffinity(0, sizeof(allowed), &allowed);
    throw;
  }
  sched_setaffinity(0, sizeof(allowed), &allowed);
  const auto code = child->waitFor(std::chrono::minutes(20));
  if (!code || *code != 0) {
    throw std::runtime_error("the solo run failed (exit " + (code ? std::to_string(*code) : std::string("none")) +
                             "); see " + spec.output_file);
  }
  std::ifstream in(dir / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  SoloCost cost;
  cost.realtime_factor = summary.at("realtime_factor").get<double>();
  cost.sim_s = summary.at("sim_s").get<double>();
  cost.wall_s = summary.at("wall_s").get<double>();
  cost.steps = summary.at("steps").get<double>();
  cost.cpu_s = child->cpuSeconds().value_or(0.0);
  cost.core = core;
  return cost;
}

}  // namespace climbsim::bench
