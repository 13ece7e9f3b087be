/// `up` and `run`: start a composition and supervise it.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/scenario_and_robot.hpp"
#include "climbsim/dds_settings.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/process.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/yaml_fields.hpp"
#include "depth_layout_check.hpp"
#include "climbsim/run_prep/run_scene.hpp"
#include "climbsim/wall/scene.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "start_on_scene.hpp"
#include "climbsim/wall/wall_coverage.hpp"
#include "commands.hpp"
#include "compose_file.hpp"
#include "detach.hpp"
#include "domain_choice.hpp"
#include "climbsim/run_summary/run_summary.hpp"
#include "climbsim/run_summary/summary_additions.hpp"
#include "climbsim/run_summary/summary_from_trace.hpp"
#include "file_lock.hpp"
#include "launch_plan.hpp"
#include "qos_depth.hpp"
#include "run_registry.hpp"
#include "run_state.hpp"
#include "security_material.hpp"
#include "signal_events.hpp"
#include "supervisor.hpp"
#include "viewer_port.hpp"

namespace climbsim::launcher {

namespace {
namespace fs = std::filesystem;

/// Highest real-time factor `--rtf` takes (0 is as fast as possible).
constexpr double kMaxRtf = 1000.0;

std::string formatDouble(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

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

/// Supervises the run made by `make` (a new Supervisor: new processes, new DDS participants)
/// and, while a secured start was given up (startAgain), makes and supervises it again, up
/// to kMaxStarts starts. Returns the last start's exit code; `supervisor` is the last.
int superviseStarts(const std::function<std::unique_ptr<Supervisor>()>& make, bool secured,
                    std::unique_ptr<Supervisor>& supervisor, DetachReport* report) {
  supervisor = make();
  int code = supervise(*supervisor, report);
  for (int starts = 1; startAgain(supervisor->processEnds(), secured, starts); ++starts) {
    spdlog::warn("a DDS Security handshake stalled before step 0 (see above): starting the run again (start {} of {})",
                 starts + 1, kMaxStarts);
    supervisor = make();
    code = supervise(*supervisor, nullptr);
  }
  return code;
}

/// The reason summary.json of a run directory gives for how it ended ("FELL at t = ...").
std::string summaryReason(const std::string& out_dir, const std::string& fallback = "FELL") {
  std::ifstream in(out_dir + "/summary.json");
  const auto summary = nlohmann::json::parse(in, nullptr, false);
  if (summary.is_discarded() || !summary.contains("reason") || !summary.at("reason").is_string() ||
      summary.at("reason").get<std::string>().empty()) {
    return fallback + " (no reason in " + out_dir + "/summary.json)";
  }
  return summary.at("reason").get<std::string>();
}

/// The scenario file `name` stands for: a path as given, or <root>/deploy/scenarios/NAME.yaml.
std::string scenarioFile(const CommandContext& context, const std::string& name) {
  if (name.find('/') != std::string::npos || fs::path(name).extension() == ".yaml") return name;
  return context.root + "/deploy/scenarios/" + name + ".yaml";
}

/// The value of `option` in a command (`--option VALUE` or `--option=VALUE`), or `fallback`.
std::string optionOf(const std::vector<std::string>& command, const std::string& option, const std::string& fallback) {
  for (std::size_t i = 1; i < command.size(); ++i) {
    if (command[i] == option && i + 1 < command.size()) return command[i + 1];
    if (command[i].rfind(option + "=", 0) == 0) return command[i].substr(option.size() + 1);
  }
  return fallback;
}

/// Each climbsim-scene service of the compose file finds its 3d Pose element and, when it
/// writes laser scans, its distance sensor in the scene (the scene service's defaults:
/// --pose-element robot_pose, --laser laser_scanner, --outputs depth,laser).
void checkSceneServices(const ComposeFile& compose, const scene::SceneDescription& description,
                        const std::string& scene_file) {
  for (const auto& service : compose.services) {
    if (service.command.empty() || fs::path(service.command.front()).filename() != "climbsim-scene") continue;
    if (optionOf(service.command, "--scene", "") != "") continue;  // a scene of its own
    const std::string where = compose.source + ":" + std::to_string(service.line) + ": services." + service.name;
    const std::string pose = optionOf(service.command, "--pose-element", "robot_pose");
    const bool has_pose = std::any_of(description.pose_elements.begin(), description.pose_elements.end(),
                                      [&](const scene::PoseElement& e) { return e.name == pose; });
    if (!has_pose) {
      throw ConfigError(scene_file + ": no 3d Pose element \"" + YamlFields::shortText(pose) +
                        "\" (it moves the robot; " + where + " looks it up)");
    }
    const std::string outputs = optionOf(service.command, "--outputs", "depth,laser");
    const std::string laser = optionOf(service.command, "--laser", "laser_scanner");
    if (outputs.find("laser") != std::string::npos && !laser.empty()) {
      const bool has_laser = std::any_of(description.distance_sensors.begin(), description.distance_sensors.end(),
                                         [&](const scene::DistanceSensorInfo& d) { return d.name == laser; });
      if (!has_laser) {
        throw ConfigError(scene_file + ": no distance_sensor \"" + YamlFields::shortText(laser) +
                          "\" (the laser scanner; " + where + " writes scans)");
      }
    }
  }
}

/// The 3d Pose element that places the robot: the compose file's scene service's
/// --pose-element, else the scene service's default.
std::string robotPoseElement(const ComposeFile& compose) {
  for (const auto& service : compose.services) {
    if (service.command.empty() || fs::path(service.command.front()).filename() != "climbsim-scene") continue;
    return optionOf(service.command, "--pose-element", "robot_pose");
  }
  return "robot_pose";
}

/// The scenario of a run, validated with everything it names before anything starts.
struct CheckedScenario {
  std::string source;  ///< the scenario file as given
  Scenario scenario;   ///< with the overrides applied
  /// The scene checked, as the `--check` line names it: the scene file, or for a scenario with
  /// a crack the pylon generated for the run (generateRunScene).
  std::string scene;
};

/// A directory made for one check (mkdtemp under the system's temporary directory), removed
/// with everything in it when the check is over.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix) {
    std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) throw ConfigError(pattern + ": cannot create a temporary directory");
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Refuses a start pose whose wheels or sealing strips already hang off the scene (or over a
/// hole deeper than the depth camera reaches): one line naming the scenario file, the start key
/// and its value. Nothing for a scene without the robot's pose element (no robot to place).
void checkStartOnScene(const CheckedScenario& checked, const std::vector<std::string>& overrides,
                       const ComposeFile& compose, scene::SceneDescription description, const RobotGeometry& geometry,
                       const std::string& scene_file) {
  const std::string element = robotPoseElement(compose);
  const bool placed = std::any_of(description.pose_elements.begin(), description.pose_elements.end(),
                                  [&](const scene::PoseElement& e) { return e.name == element; });
  if (!placed) return;
  const double reach_m = scene::coverageReach(description);
  const scene::Scene world(std::move(description));
  const scene::WallCoverage coverage = scene::wallCoverage(world, element, reach_m);
  const auto& start = checked.scenario.start;
  const OffScene off = offSceneAt(coverage, geometry, start.x_m, start.y_m, start.yaw_deg * M_PI / 180.0);
  const auto message = startOffSceneMessage(
      off, coverage, start.x_m, start.y_m, start.yaw_deg,
      [&](const std::string& key) { return scenarioKeyWhere(checked.source, overrides, key); }, scene_file);
  if (message) throw ConfigError(*message);
}

/// Validates the scenario (overrides applied) and the robot and scene files it names; nothing
/// when there is no scenario. Throws ConfigError with the problems of the first bad file.
std::optional<CheckedScenario> checkScenario(const CommandContext& context, const UpOptions& options,
                                             const ComposeFile& compose) {
  const std::string source = options.scenario.empty() ? compose.scenario : scenarioFile(context, options.scenario);
  if (source.empty()) {
    if (!options.overrides.empty()) throw ConfigError("--set needs a scenario (--scenario, or scenario: in the compose file)");
    return std::nullopt;
  }
  if (options.scenario.empty() && !std::ifstream(source)) {
    throw ConfigError(compose.source + ":" + std::to_string(compose.scenario_line) + ": scenario = " +
                      YamlFields::shortText(source) + ": cannot read the scenario file");
  }
  CheckedScenario checked{source, loadScenario(source, options.overrides), {}};
  for (const auto& note : checked.scenario.ignored) spdlog::warn("{}", note);  // e.g. --set controller.type=none
  // What every service will load must load here first: one line before anything starts.
  const RobotGeometry geometry = scenarioAndRobot(checked.scenario).geometry;
  std::string scene = checked.scenario.scenePath(context.build_dir);
  checked.scene = scene;
  if (!std::ifstream(scene)) {
    throw ConfigError(source + ": scene = " + YamlFields::shortText(checked.scenario.scene_file) + ": cannot read '" +
                      scene + "'");
  }
  // A scenario with a crack runs on a pylon generated for it (prepareScenario: RUN_DIR/scene),
  // not on the build's: the same pylon (same seed and crack, same bytes) is generated into a
  // scratch directory and that is the scene checked.
  std::optional<ScratchDir> generated;
  if (checked.scenario.crack) {
    generated.emplace("climbsim-check-scene");
    scene = surface::generateRunScene(checked.scenario, generated->path());
    checked.scene = checked.scenario.scenePath(context.build_dir) + " generated with crack {depth_m: " +
                    formatDouble(checked.scenario.crack->depth_m) +
                    ", width_m: " + formatDouble(checked.scenario.crack->width_m) + "}";
  }
  // The scene XML and every mesh it names, as the scene service will load them, and the
  // elements the compose file's scene services will look up.
  scene::SceneDescription description = scene::loadSceneDescription(scene);
  checkSceneServices(compose, description, checked.scene);
  checkDepthLayout(compose, checked.scenario, description);
  checkStartOnScene(checked, options.overrides, compose, std::move(description), geometry, checked.scene);
  return checked;
}

/// Writes the resolved copy of the scenario into the run's output directory and says what the
/// plan needs of it.
ScenarioRun prepareScenario(const CommandContext& context, const UpOptions& options, const CheckedScenario& checked,
                            const std::string& default_out_dir) {
  ScenarioRun run;
  run.out_dir = fs::absolute(options.out_dir.empty() ? default_out_dir : options.out_dir).lexically_normal().string();
  fs::create_directories(run.out_dir);
  // A scenario with a crack gets its own pylon in RUN_DIR/scene (run_scene.hpp).
  const std::string text = surface::runScenarioText(checked.source, options.overrides, context.build_dir, run.out_dir);
  run.scenario_file = run.out_dir + "/scenario.yaml";
  // What an earlier run left here is not this run's: the progress line reads trace.csv.
  for (const char* stale : {"trace.csv", "summary.json"}) {
    fs::remove(fs::path(run.out_dir) / stale);
  }
  // Nor are its plots and pictures: a shorter run would show an earlier run's later ones.
  for (const char* stale : {"plots", "pictures"}) {
    fs::remove_all(fs::path(run.out_dir) / stale);
  }
  std::ofstream(run.scenario_file) << text;
  const Scenario& scenario = checked.scenario;
  run.step_ms = static_cast<double>(scenario.step_ns) * 1e-6;
  run.duration_s = scenario.duration_s;
  run.depth_period = static_cast<std::uint32_t>(scenario.depthPeriodSteps());
  run.laser_period = static_cast<std::uint32_t>(scenario.laserPeriodSteps());
  run.robot_file = scenario.robotPath();
  spdlog::info("scenario '{}' from {} ({} s at {} ms steps); run directory {}", scenario.name, checked.source,
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
  {
    // A run that ended before its first row (bad input, a start that failed) has nothing to plot.
    std::ifstream trace(fs::path(out_dir) / "trace.csv");
    std::string header, row;
    if (!std::getline(trace, header) || !std::getline(trace, row) || row.empty()) return;
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
  // A second run's viewer finds 8765 taken by the first's: it takes the next free port.
  letViewersFindAFreePort(compose);
  if (options.window_steps) compose.clock.window_steps = options.window_steps;
  if (compose.clock.window_steps) {
    // The clock refuses it too, but only once every service has started.
    const char* qos_env = std::getenv("CLIMBSIM_QOS_FILE");
    checkWindowFitsQueues(*compose.clock.window_steps,
                          qos_env && *qos_env ? std::string(qos_env) : context.root + "/deploy/qos/climbsim.xml");
  }
  if (options.rtf) {
    if (!std::isfinite(*options.rtf) || *options.rtf < 0.0 || *options.rtf > kMaxRtf) {
      throw ConfigError("--rtf " + formatDouble(*options.rtf) + ": it must be a number in [0, " +
                        formatDouble(kMaxRtf) + "] (0: as fast as possible)");
    }
    compose.clock.rtf = *options.rtf;
  }
  if (options.domain) {
    if (*options.domain < 0 || *options.domain > kMaxDomainId) {
      throw ConfigError("--domain " + std::to_string(*options.domain) + ": it must be an integer in 0.." +
                        std::to_string(kMaxDomainId));
    }
    compose.domain_id = *options.domain;
  }
  if (!options.name.empty()) validateRunName(options.name);
  if (options.secure) compose.security = true;
  // A secured run grants each participant its program's topics: refused here, before anything
  // starts, if a service's program has none (a Python or C client).
  const std::vector<SecurityGrant> grants = compose.security ? securityGrants(compose) : std::vector<SecurityGrant>();
  const std::optional<CheckedScenario> checked = checkScenario(context, options, compose);
  const char* path_env = std::getenv("PATH");
  const ExecutableSearch search =
      executableSearch(context.compose_file, context.build_dir, path_env != nullptr ? path_env : "");
  if (options.check) {
    // The plan as a run would make it (programs found, periods and offsets, hosts), on no domain.
    std::optional<ScenarioRun> planned;
    if (checked) {
      planned.emplace();
      planned->scenario_file = checked->source;
      planned->out_dir = "<out>";
      planned->step_ms = static_cast<double>(checked->scenario.step_ns) * 1e-6;
      planned->duration_s = checked->scenario.duration_s;
      planned->depth_period = static_cast<std::uint32_t>(checked->scenario.depthPeriodSteps());
      planned->laser_period = static_cast<std::uint32_t>(checked->scenario.laserPeriodSteps());
      planned->robot_file = checked->scenario.robotPath();
    }
    buildLaunchPlan(compose, compose.domain_id.value_or(kAutoDomainFirst), search, planned);
    checkHosts(compose, search.path_env);
    std::cout << "ok: " << compose.source;
    if (checked) {
      std::cout << ", " << checked->source << ", " << checked->scenario.robotPath() << ", " << checked->scene;
    }
    std::cout << std::endl;
    return kExitOk;
  }

  const std::string base = !options.name.empty() ? options.name
                           : checked                ? baseRunName(checked->scenario.name)
                                                    : baseRunName(compose.name);
  std::optional<ClaimedRun> claimed = claimRun(context.build_dir, base, !options.name.empty());
  if (!claimed) {
    const RunPaths taken(context.build_dir, base);
    const auto owner = FileLock::readOwner(taken.lock_file);
    spdlog::error("a run named '{}' is already running{}; choose another --name or stop it with 'down {}'", base,
                  owner ? " (supervisor pid " + std::to_string(*owner) + ")" : std::string(), base);
    return 1;
  }
  const std::string& run_name = claimed->name;
  const RunPaths& paths = claimed->paths;
  FileLock* run_lock = &claimed->lock;
  run_lock->writeOwner(::getpid());
  std::optional<ScenarioRun> scenario;
  if (checked) scenario = prepareScenario(context, options, *checked, paths.dir + "/out");

  std::optional<DomainLease> domain;
  try {
    domain.emplace(leaseRunDomain(compose.domain_id));
  } catch (const std::runtime_error& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  checkHosts(compose, search.path_env);
  std::string security_dir;
  if (compose.security) {
    // In the run directory (with the trace when there is one), the same path on every host.
    security_dir = (fs::path(scenario ? scenario->out_dir : paths.dir) / kSecurityDirName).string();
    try {
      makeSecurityMaterial(security_dir, domain->id(), grants, search.path_env);
      copySecurityMaterial(compose, security_dir, grants);
    } catch (const ConfigError&) {
      throw;
    } catch (const std::runtime_error& e) {
      spdlog::error("{}", e.what());
      return 1;
    }
    spdlog::info("DDS Security on: run CA, {} identities and their permissions in {}", grants.size(), security_dir);
  }
  // Each start has its own run id: a late sample of a given-up start is not this one's.
  const auto makePlan = [&] { return buildLaunchPlan(compose, domain->id(), search, scenario, randomRunId(), security_dir); };
  const LaunchPlan plan = makePlan();

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
  state.name = run_name;
  state.compose_name = compose.name;
  state.scenario = checked ? fs::absolute(checked->source).lexically_normal().string() : std::string();
  state.out_dir = scenario ? scenario->out_dir : std::string();
  state.rtf = compose.clock.rtf;
  state.compose_file = fs::absolute(context.compose_file).lexically_normal().string();
  state.run_dir = paths.dir;
  state.detached = options.detach;
  state.domain_id = domain->id();
  state.started_at = localTimestamp();

  // Makes the supervisor of each start: the first with `plan`, a later one with a new plan.
  int starts = 0;
  const auto makeSupervisor = [&](SignalEvents& signals) {
    return [&, events = &signals]() {
      return std::make_unique<Supervisor>(starts++ == 0 ? plan : makePlan(), paths, state, supervisor_options, *events);
    };
  };

  if (options.detach) {
    const int code = runDetached(paths.supervisor_log, [&](DetachReport& report) {
      run_lock->writeOwner(::getpid());
      state.supervisor_pid = ::getpid();
      spdlog::info("supervising '{}' on DDS domain {} (pid {})", run_name, state.domain_id, state.supervisor_pid);
      SignalEvents signals;
      std::unique_ptr<Supervisor> last;
      const int run_code = superviseStarts(makeSupervisor(signals), compose.security, last, &report);
      Supervisor& supervisor = *last;
      spdlog::info("the run ended with exit code {}", run_code);
      if (scenario) {
        run_summary::ensureSummary(scenario->out_dir, checked->scenario.name, run_code, supervisor.firstFailure());
        agreeOnConfigError(scenario->out_dir, run_code, configCulprit(supervisor.processEnds()).value_or(""));
        run_summary::addDroppedSamples(scenario->out_dir, supervisor.droppedSamples());
        run_summary::addWheelsOverNothing(scenario->out_dir, supervisor.wheelsOverNothing());
        run_summary::fillFailureReason(scenario->out_dir, supervisor.clockFailure());
        plotRun(context, scenario->out_dir);
      }
      return run_code;
    });
    if (code == 0) {
      spdlog::info("'{}' runs in the background on DDS domain {}; see 'ps', 'logs {}', 'down {}'", run_name,
                   state.domain_id, run_name, run_name);
      std::cout << paths.dir << std::endl;
    }
    return code;
  }

  state.supervisor_pid = ::getpid();
  spdlog::info("starting '{}' on DDS domain {} ({} services; logs in {})", run_name, state.domain_id,
               plan.processes.size() - 1, paths.logs_dir);
  SignalEvents signals;
  std::unique_ptr<Supervisor> last;
  const int code = superviseStarts(makeSupervisor(signals), compose.security, last, nullptr);
  Supervisor& supervisor = *last;
  if (scenario) {
    // The recorder writes summary.json; if it died, the launcher writes one (any outcome).
    run_summary::ensureSummary(scenario->out_dir, checked->scenario.name, code, supervisor.firstFailure());
    // A service that refused its configuration makes the run exit 2: the summary says so too.
    agreeOnConfigError(scenario->out_dir, code, configCulprit(supervisor.processEnds()).value_or(""));
    run_summary::addDroppedSamples(scenario->out_dir, supervisor.droppedSamples());  // sum what every service dropped
    run_summary::addWheelsOverNothing(scenario->out_dir, supervisor.wheelsOverNothing());  // the drive's warnings
    run_summary::fillFailureReason(scenario->out_dir, supervisor.clockFailure());  // a recorder that saw no Stop
    plotRun(context, scenario->out_dir);
  }
  const std::string slid = code == 0 && scenario ? run_summary::slideBeyondLimitOf(scenario->out_dir) : std::string();
  if (code == 0 && !slid.empty()) {
    spdlog::warn("'{}' completed, but {}", run_name, slid);
  } else if (code == 0) {
    spdlog::info("'{}' completed", run_name);
  } else if (code == kExitFell) {
    spdlog::error("{} (exit code {}; end_on.fall=false simulates the fall to the end)",
                  scenario ? summaryReason(scenario->out_dir) : std::string("FELL"), code);
  } else if (code == kExitStopped) {
    spdlog::warn("'{}' stopped before its end (exit code {})", run_name, code);
  } else if (code == kExitConfig) {
    const auto culprit = configCulprit(supervisor.processEnds());
    spdlog::error("'{}' ended with exit code 2 (bad configuration): {}", run_name,
                  scenario ? summaryReason(scenario->out_dir, culprit ? "service '" + *culprit + "' refused its configuration"
                                                                      : std::string("the clock refused the configuration"))
                           : (culprit ? "service '" + *culprit + "' refused its configuration" : std::string("see above")));
  } else {
    // The reason summary.json gives (the clock's Stop), unless a stopped process says more.
    const std::string why = !supervisor.stoppedNote().empty() || !scenario
                                ? supervisor.stoppedNote()
                                : ": " + summaryReason(scenario->out_dir, "no reason");
    spdlog::error("'{}' ended with exit code {}{}", run_name, code, why);
  }
  return code;
}

}  // namespace climbsim::launcher
