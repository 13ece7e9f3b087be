/// `up` and `run`: start a composition and supervise it.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/process.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "commands.hpp"
#include "compose_file.hpp"
#include "detach.hpp"
#include "domain_choice.hpp"
#include "file_lock.hpp"
#include "launch_plan.hpp"
#include "run_state.hpp"
#include "signal_events.hpp"
#include "supervisor.hpp"

namespace climbsim::launcher {

namespace {
namespace fs = std::filesystem;

/// A new run starts with empty logs: old files of processes no longer in the file go too.
void clearLogs(const std::string& logs_dir) {
  fs::create_directories(logs_dir);
  for (const auto& entry : fs::directory_iterator(logs_dir)) {
    if (entry.path().extension() == ".log") {
      fs::remove(entry.path());
    }
  }
}

int supervise(Supervisor& supervisor, DetachReport* report) {
  try {
    supervisor.start();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    if (report != nullptr) {
      report->failed(1, e.what());
    }
    return 1;
  }
  if (report != nullptr) {
    report->ready();
  }
  return supervisor.wait();
}

/// The scenario file `name` stands for: a path as given, or <root>/deploy/scenarios/NAME.yaml.
std::string scenarioFile(const CommandContext& context, const std::string& name) {
  if (name.find('/') != std::string::npos || fs::path(name).extension() == ".yaml") return name;
  return context.root + "/deploy/scenarios/" + name + ".yaml";
}

/// Validates the scenario, writes its resolved copy into the run's output directory and says
/// what the plan needs of it; nothing when there is no scenario.
std::optional<ScenarioRun> prepareScenario(const CommandContext& context, const UpOptions& options,
                                           const ComposeFile& compose, const std::string& default_out_dir) {
  const std::string source = options.scenario.empty() ? compose.scenario : scenarioFile(context, options.scenario);
  if (source.empty()) {
    if (!options.overrides.empty()) throw ConfigError("--set needs a scenario (--scenario, or scenario: in the compose file)");
    return std::nullopt;
  }
  const std::string text = resolvedScenarioText(source, options.overrides, context.build_dir);
  ScenarioRun run;
  run.out_dir = fs::absolute(options.out_dir.empty() ? default_out_dir : options.out_dir).lexically_normal().string();
  fs::create_directories(run.out_dir);
  run.scenario_file = run.out_dir + "/scenario.yaml";
  // What an earlier run left here is not this run's: the progress line reads trace.csv.
  for (const char* stale : {"trace.csv", "summary.json"}) {
    fs::remove(fs::path(run.out_dir) / stale);
  }
  std::ofstream(run.scenario_file) << text;
  const Scenario scenario = loadScenario(run.scenario_file);
  // What every service will load must load here first: one line before anything starts.
  computeGeometry(loadRobotDescription(scenario.robotPath()));
  const std::string scene = scenario.scenePath(context.build_dir);
  if (!std::ifstream(scene)) {
    throw ConfigError(source + ": scene = " + scenario.scene_file + ": cannot read '" + scene + "'");
  }
  run.step_ms = static_cast<double>(scenario.step_ns) * 1e-6;
  run.duration_s = scenario.duration_s;
  run.depth_period = static_cast<std::uint32_t>(scenario.depthPeriodSteps());
  run.laser_period = static_cast<std::uint32_t>(scenario.laserPeriodSteps());
  spdlog::info("scenario '{}' from {} ({} s at {} ms steps); run directory {}", scenario.name, source,
               scenario.duration_s, run.step_ms, run.out_dir);
  return run;
}

/// Draws the plots of a finished run (climbsim-plot RUN_DIR: RUN_DIR/plots/*.png), also after a
/// run that failed: what was computed is plotted. A plot failure is reported, not the run's.
void plotRun(const CommandContext& context, const std::string& out_dir) {
  const std::string program = context.build_dir + "/bin/climbsim-plot";
  if (::access(program.c_str(), X_OK) != 0) {
    spdlog::warn("no plots: {} is not built", program);
    return;
  }
  if (!fs::exists(fs::path(out_dir) / "trace.csv")) {
    return;  // the run ended before its first step
  }
  ProcessSpec spec;
  spec.argv = {program, out_dir};
  fs::create_directories(fs::path(out_dir) / "logs");
  spec.output_file = (fs::path(out_dir) / "logs" / "plot.log").string();
  fs::remove(spec.output_file);
  ChildProcess plot(spec);
  const auto code = plot.waitFor(std::chrono::minutes(5));
  if (code && *code == 0) {
    spdlog::info("plots in {}/plots", out_dir);
  } else {
    spdlog::warn("the plots failed (exit {}); see {}", code ? std::to_string(*code) : "none: killed after 5 min",
                 spec.output_file);
  }
}
}  // namespace

int commandUp(const CommandContext& context, const UpOptions& options) {
  ComposeFile compose = loadComposeFile(context.compose_file);
  if (!options.observers) {
    compose.services.erase(std::remove_if(compose.services.begin(), compose.services.end(),
                                          [](const ServiceSpec& service) { return service.observer; }),
                           compose.services.end());
  }
  const RunPaths paths(context.build_dir, compose.name);
  fs::create_directories(paths.dir);
  const std::optional<ScenarioRun> scenario = prepareScenario(context, options, compose, paths.dir + "/out");

  auto run_lock = FileLock::tryLock(paths.lock_file);
  if (!run_lock) {
    const auto owner = FileLock::readOwner(paths.lock_file);
    spdlog::error("'{}' is already running{}; stop it with 'down' first", compose.name,
                  owner ? " (supervisor pid " + std::to_string(*owner) + ")" : std::string());
    return 1;
  }
  run_lock->writeOwner(::getpid());

  std::optional<DomainLease> domain;
  try {
    domain.emplace(leaseRunDomain(compose.domain_id));
  } catch (const std::runtime_error& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  const char* path_env = std::getenv("PATH");
  const ExecutableSearch search{context.build_dir + "/bin", fs::absolute(context.compose_file).parent_path().string(),
                                path_env != nullptr ? path_env : ""};
  const LaunchPlan plan = buildLaunchPlan(compose, domain->id(), search, scenario);
  checkHosts(compose, search.path_env);

  clearLogs(paths.logs_dir);
  SupervisorOptions supervisor_options;
  supervisor_options.to_terminal = !options.detach;
  supervisor_options.color = !options.detach && terminalWantsColor();
  supervisor_options.shield_interrupt = !options.detach;
  if (!options.out_dir.empty()) {
    const std::string out_logs = (fs::path(options.out_dir) / "logs").string();
    fs::create_directories(out_logs);
    supervisor_options.extra_log_dirs.push_back(out_logs);
  }
  if (scenario) {
    supervisor_options.progress_trace = scenario->out_dir + "/trace.csv";
    supervisor_options.progress_duration_s = scenario->duration_s;
    supervisor_options.progress_live = !options.detach && ::isatty(STDOUT_FILENO) != 0;
  }
  RunState state;
  state.compose_name = compose.name;
  state.compose_file = fs::absolute(context.compose_file).lexically_normal().string();
  state.run_dir = paths.dir;
  state.detached = options.detach;
  state.domain_id = domain->id();
  state.started_at = localTimestamp();

  if (options.detach) {
    const int code = runDetached(paths.supervisor_log, [&](DetachReport& report) {
      run_lock->writeOwner(::getpid());
      state.supervisor_pid = ::getpid();
      spdlog::info("supervising '{}' on DDS domain {} (pid {})", compose.name, state.domain_id, state.supervisor_pid);
      SignalEvents signals;
      Supervisor supervisor(plan, paths, state, supervisor_options, signals);
      const int run_code = supervise(supervisor, &report);
      spdlog::info("the run ended with exit code {}", run_code);
      if (scenario) plotRun(context, scenario->out_dir);
      return run_code;
    });
    if (code == 0) {
      spdlog::info("'{}' runs in the background on DDS domain {}; see 'ps', 'logs', 'down'", compose.name,
                   state.domain_id);
      std::cout << paths.dir << std::endl;
    }
    return code;
  }

  state.supervisor_pid = ::getpid();
  spdlog::info("starting '{}' on DDS domain {} ({} services; logs in {})", compose.name, state.domain_id,
               plan.processes.size() - 1, paths.logs_dir);
  SignalEvents signals;
  Supervisor supervisor(plan, paths, state, supervisor_options, signals);
  const int code = supervise(supervisor, nullptr);
  if (scenario) plotRun(context, scenario->out_dir);
  if (code == 0) {
    spdlog::info("'{}' completed", compose.name);
  } else {
    spdlog::error("'{}' ended with exit code {}", compose.name, code);
  }
  return code;
}

}  // namespace climbsim::launcher
