/// climbsim-bench-e2e: the whole closed loop, every service a separate process on this
/// machine (deploy/compose.yaml), running a scenario (default crack-descent) as fast as it
/// can. Prints
///   bench: e2e: scenario=crack-descent sim_s=20 wall_s=.. realtime_factor=.. target=20 met=..
///   bench: e2e: cpu_share clock=..% scene=..% sealing=..% thermo=..% drive=..% ...
/// and writes the same as JSON to --out. The real-time factor is the recorder's: simulated
/// time over the wall time from the first step to the last. CPU shares are each process's
/// user + system time (the launcher records them at exit) over the sum of all; cpu_cores is
/// that sum over the wall time of the whole launcher run (start-up included): how many of the
/// machine's cores the run kept busy.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/process.hpp"

namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw climbsim::ConfigError(path.string() + ": not written by the run");
  return nlohmann::json::parse(in);
}

/// The service a roster name belongs to: "sealing-1" -> "sealing".
std::string serviceOf(const std::string& process) {
  const auto dash = process.rfind('-');
  if (dash != std::string::npos && dash + 1 < process.size() &&
      process.find_first_not_of("0123456789", dash + 1) == std::string::npos) {
    return process.substr(0, dash);
  }
  return process;
}

struct Options {
  std::string out_file;
  std::string root = CLIMBSIM_ROOT;
  std::string build = CLIMBSIM_BUILD_DIR;
  std::string scenario = "crack-descent";
  std::string run_name = "bench-e2e";  ///< `run --name`: the launcher's state is <build>/run/<name>/state.json
  double target = 20.0;
};

int run(const Options& options) {
  const std::string& root = options.root;
  const std::string& build = options.build;
  const std::string& scenario = options.scenario;
  const std::string& out_file = options.out_file;
  const double target = options.target;

  const fs::path run_dir = fs::path(build) / "bench" / "e2e-run";
  fs::remove_all(run_dir);
  climbsim::ProcessSpec spec;
  spec.argv = {build + "/bin/climbsim-compose", "--root", root, "--build", build, "run", scenario, "--name",
               options.run_name, "--out", run_dir.string()};
  fs::create_directories(run_dir.parent_path());
  spec.output_file = (fs::path(build) / "bench" / "e2e-run.log").string();
  fs::remove(spec.output_file);
  const auto start = std::chrono::steady_clock::now();
  climbsim::ChildProcess launcher(spec);
  const auto code = launcher.waitFor(std::chrono::minutes(20));
  const double launcher_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!code || *code != 0) {
    std::fprintf(stderr, "bench e2e: the run failed (exit %s); see %s\n", code ? std::to_string(*code).c_str() : "none",
                 spec.output_file.c_str());
    return 1;
  }

  const auto summary = readJson(run_dir / "summary.json");
  // The launcher keeps the state of a run under <build>/run/<run name>/state.json.
  const auto state = readJson(fs::path(build) / "run" / options.run_name / "state.json");
  std::map<std::string, double> cpu_by_service;
  double cpu_total = 0.0;
  for (const auto& process : state.at("processes")) {
    if (process.at("cpu_s").is_null()) continue;
    const double cpu = process.at("cpu_s").get<double>();
    cpu_by_service[serviceOf(process.at("name").get<std::string>())] += cpu;
    cpu_total += cpu;
  }
  const double sim_s = summary.at("sim_s").get<double>();
  const double wall_s = summary.at("wall_s").get<double>();
  const double rtf = summary.at("realtime_factor").get<double>();
  const bool met = rtf >= target;

  std::printf("bench: e2e: scenario=%s sim_s=%g wall_s=%.3f realtime_factor=%.2f target=%g met=%s "
              "launcher_wall_s=%.2f cpu_s=%.2f cpu_cores=%.2f\n",
              scenario.c_str(), sim_s, wall_s, rtf, target, met ? "true" : "false", launcher_wall_s, cpu_total,
              cpu_total / launcher_wall_s);
  std::ostringstream shares;
  nlohmann::json share_json;
  for (const auto& [service, cpu] : cpu_by_service) {
    const double share = cpu_total > 0.0 ? 100.0 * cpu / cpu_total : 0.0;
    char text[96];
    std::snprintf(text, sizeof(text), " %s=%.1f%%", service.c_str(), share);
    shares << text;
    share_json[service] = {{"cpu_s", cpu}, {"share_percent", share}, {"cpu_per_sim_s", cpu / sim_s}};
  }
  std::printf("bench: e2e: cpu_share%s\n", shares.str().c_str());
  if (!out_file.empty()) {
    nlohmann::json json = {{"scenario", scenario},         {"sim_s", sim_s},   {"wall_s", wall_s},
                           {"realtime_factor", rtf},       {"target", target}, {"met", met},
                           {"launcher_wall_s", launcher_wall_s}, {"cpu_s", cpu_total},
                           {"cpu_cores", cpu_total / launcher_wall_s}, {"services", share_json}};
    std::ofstream(out_file) << json.dump(2) << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-e2e: real-time factor and CPU shares of the whole closed loop"};
  Options options;
  app.add_option("--out", options.out_file, "JSON file to write");
  app.add_option("--root", options.root, "the climbsim checkout");
  app.add_option("--build", options.build, "the build directory");
  app.add_option("--scenario", options.scenario, "scenario name or file (deploy/compose.yaml runs it)");
  app.add_option("--target", options.target, "real-time factor to reach");
  return climbsim::guardedMain(app, argc, argv, "bench-e2e", [&] { return run(options); });
}
