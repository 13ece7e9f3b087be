/// climbsim-bench-e2e: the whole closed loop, every service a separate process on this
/// machine (deploy/compose.yaml), running a scenario (default crack-descent) as fast as it
/// can, once with the clock's window W = 1 (one grant per step, the classic lockstep) and once
/// with the default W, plus the raw Fast DDS round trip measured in the same run. Prints
///
///   bench: e2e: scenario=.. realtime_factor=.. realtime_factor_w1=.. speedup_vs_w1=..
///               deliveries_per_step=.. ctx_switches_per_step=.. rtt_us=.. step_over_rtt=.. ...
///   bench: e2e: depth_frame_ms render=.. publish_cpu=.. receive_cpu=.. sealing_model=.. ...
///   bench: e2e: loop_bound ...     (the scene -> sealing -> thermo -> drive -> scene loop)
///   bench: e2e: viewer round K: ...  (pairs of runs without and with the viewer and a headless
///               Chromium attached, one after the other; --viewer-rounds, default 3)
///   bench: e2e: viewer realtime_factor_viewer=.. realtime_factor=.. viewer_cost=..%  (the
///               median pair's cost; --no-viewer skips them)
///   bench: e2e: viewer_service realtime_factor_viewer_service=..  (a fourth: the viewer, no page)
///   bench: e2e: recording round K (without|with first): ...  (rounds of a run without run.mcap
///               and one with it, in alternating order, with the load average; --recording-rounds,
///               default 5)
///   bench: e2e: recording recording_cost=..% ... reference: realtime_factor_without_mcap=..
///               (the median round's ratio; --recording-only runs these rounds alone)
///   bench: e2e: security round K (unsecured|secured first): ...  (rounds of an unsecured run and a
///               secured one, `run --secure`, in alternating order, with the load average and
///               each service's CPU; --security-rounds, default 3)
///   bench: e2e: security realtime_factor_secured=.. realtime_factor=.. security_cost=..% ...
///               security_cpu_cost=..% same_trace=..  (the median round's; docs/security.md says
///               what each topic's protection is; --no-secure skips them, --security-only runs
///               them alone)
///   bench: e2e: distributed_over_solo=.. realtime_factor=.. realtime_factor_solo=..  (the same
///               scenario in one process on one core, no DDS: climbsim-solo, in this run)
///   bench: e2e: speed render_ms=.. sealing_step_ms=.. drive_step_ms=.. loop_bound_rtf=..
///               realtime_factor=.. realtime_factor_solo=.. rtf_over_loop_bound=.. cpu_bound_rtf=..
///               rtf_over_cpu_bound=.. security_cost=..  (the speed figures side by side, each with
///               its reference; cpu_bound_rtf = sim_s x cores / the roster members' CPU from their first step)
///   bench: e2e: per_step <service>=<deliveries>/<ctx switches> ...
///   bench: e2e: cpu_share clock=..% scene=..% ...
///   bench: e2e: robots round K: realtime_factor (over cromsci's): cromsci=.. (1.000) grid-2x2=.. (..) ...
///   bench: e2e: robot=cromsci scenario=crack-descent realtime_factor=.. deliveries_per_step=.. (...)
///   bench: e2e: robot=NAME scenario=crack-NAME realtime_factor=.. deliveries_per_step=.. rtf_over_cromsci=..
///               (each shipped robot's crack scenario beside CROMSCI's, --robot NAME|all|none, medians
///               of --robot-rounds rounds; a robot without a crack scenario: "robot=NAME skipped: ...";
///               --robots-only runs these alone)
///
/// and writes the same as JSON to --out. Real-time factors are the recorder's (simulated time
/// over the wall time from the first step to the last, scene loading before step 0 left
/// out: it is reported as scene_load_s). Deliveries are samples taken by every process's
/// readers (each one a Fast DDS delivery to the application; CLIMBSIM_STATS_DIR statistics of
/// common/run_stats), context switches are the kernel's counters of every process's threads
/// (wait4 rusage, recorded by the launcher in state.json). Every ratio is printed beside
/// what it divides by.

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/domain_lease.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/process.hpp"
#include "climbsim/robot_names.hpp"
#include "solo/solo_rtf.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

json readJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw climbsim::ConfigError(path.string() + ": not written by the run");
  return json::parse(in);
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
  std::string run_name = "bench-e2e";     ///< `run --name`: the launcher's state is <build>/run/<name>/state.json
  double target = 20.0;                   ///< real-time factor to reach
  double step_over_rtt_target = 2.5;      ///< e2e wall time per step / raw round trip, at most
  double speedup_target = 1.5;            ///< default W over W = 1, at least
  bool viewer = true;                     ///< also a run with the viewer and a headless browser
  int viewer_rounds = 3;                  ///< pairs of runs without / with the viewer (median cost)
  int recording_rounds = 5;               ///< rounds of a run without and one with run.mcap (median ratio)
  bool recording_only = false;            ///< only the recording rounds (measureRecordingCost)
  bool secure = true;                     ///< also runs with DDS Security (`run --secure`)
  int security_rounds = 3;                ///< rounds of an unsecured and a secured run (median cost)
  bool security_only = false;             ///< only the security rounds (measureSecurityCost)
  std::string compose;                    ///< compose file (`run -f`); "" = deploy/compose.yaml
  std::vector<std::string> sets;          ///< scenario overrides (`run --set`)
  bool hires = false;                     ///< only the leakage-bound comparison (`bench: e2e-hires:`)
  double hires_duration_s = 3.0;          ///< simulated seconds of each hires run
  std::string hires_compose;              ///< the 2-shard layout; "" = deploy/compose.hires-shards.yaml
  int hires_rounds = 3;                   ///< rounds of the three hires layouts (median ratios)
  std::string robot = "all";              ///< the shipped robot compared with CROMSCI, "all" or "none"
  int robot_rounds = 3;                   ///< rounds of the robots' crack runs (median ratios)
  bool robots_only = false;               ///< only the robots' comparison (no W = 1, viewer, ...)
  double robot_target = 0.7;              ///< a robot's realtime_factor / CROMSCI's, at least
};

/// One run of the scenario through the launcher and what it cost.
struct RunCost {
  std::string label;
  std::string outcome;  ///< the summary's: completed, fell, ...
  double sim_s = 0, wall_s = 0, rtf = 0, launcher_wall_s = 0, cpu_s = 0;
  double steps = 0;
  double deliveries = 0, ctx_switches = 0;
  std::map<std::string, double> cpu_by_service, deliveries_by_service, ctx_by_service;
  std::map<std::string, json> stats;  ///< by process: its CLIMBSIM_STATS_DIR counters
  double browser_cpu_s = 0;           ///< the attached headless browser (node and its Chromium)
  std::string browser_cpu_by_type;  ///< the attach script's by_type: CPU s per Chromium process type
};

/// deploy/compose.yaml with its text `from` replaced by `to`, as <build>/bench/`file_name`
/// (programs are found in <build>/bin; the scenario is given on the command line).
std::string composeVariant(const Options& o, const std::string& from, const std::string& to,
                           const std::string& file_name) {
  std::ifstream in(o.root + "/deploy/compose.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const auto at = yaml.find(from);
  if (at == std::string::npos) throw std::runtime_error("deploy/compose.yaml: no '" + from + "' to change");
  yaml.replace(at, from.size(), to);
  const std::string path = o.build + "/bench/" + file_name;
  std::ofstream(path) << yaml;
  return path;
}

/// deploy/compose.yaml with the clock starting paused.
std::string pausedComposeFile(const Options& o) {
  return composeVariant(o, "clock: {rtf: 0,", "clock: {rtf: 0, start_paused: true,", "compose.e2e-viewer.yaml");
}

/// deploy/compose.yaml with the recorder writing no run.mcap (--no-mcap): the runs that tell
/// what recording costs.
std::string noMcapComposeFile(const Options& o) {
  return composeVariant(o, "--depth-grids]", "--depth-grids, --no-mcap]", "compose.e2e-no-mcap.yaml");
}

/// With `viewer`, the run starts the viewer (run --viewer) and a headless Chromium is attached
/// to it for the whole run (tests/system/viewer/attach_browser.mjs).
/// `attach` false: the viewer runs with no page connected (what the service itself costs).
/// `secure`: the run with DDS Security (`run --secure`).
RunCost runScenario(const Options& o, const std::string& label, std::optional<int> window, bool viewer = false,
                    bool attach = true, bool secure = false) {
  const fs::path run_dir = fs::path(o.build) / "bench" / ("e2e-" + label);
  fs::remove_all(run_dir);
  const fs::path stats_dir = run_dir / "stats";
  fs::create_directories(stats_dir);
  climbsim::ProcessSpec spec;
  spec.argv = {o.build + "/bin/climbsim-compose", "--root", o.root, "--build", o.build, "run", o.scenario,
               "--name", o.run_name, "--out", run_dir.string()};
  if (viewer && attach) {
    // The clock holds before step 0 until the attached page presses resume: the browser's
    // start-up (seconds of CPU) is not part of the run; the viewer and the page at work are.
    spec.argv.insert(spec.argv.end(), {"-f", pausedComposeFile(o)});
  }
  if (window) spec.argv.insert(spec.argv.end(), {"--window-steps", std::to_string(*window)});
  if (viewer) spec.argv.emplace_back("--viewer");
  if (secure) spec.argv.emplace_back("--secure");
  if (!o.compose.empty()) spec.argv.insert(spec.argv.end(), {"-f", o.compose});
  for (const auto& set : o.sets) spec.argv.insert(spec.argv.end(), {"--set", set});
  spec.env["CLIMBSIM_STATS_DIR"] = stats_dir.string();
  spec.output_file = (fs::path(o.build) / "bench" / ("e2e-" + label + ".log")).string();
  fs::remove(spec.output_file);
  const auto start = std::chrono::steady_clock::now();
  climbsim::ChildProcess launcher(spec);
  std::optional<climbsim::ChildProcess> browser;
  const std::string attach_log = (fs::path(o.build) / "bench" / ("e2e-" + label + "-browser.log")).string();
  if (viewer && attach) {
    climbsim::ProcessSpec attach;
    attach.argv = {"node", o.root + "/tests/system/viewer/attach_browser.mjs", "--build", o.build, "--url",
                   "http://127.0.0.1:8765/", "--resume"};
    attach.output_file = attach_log;
    fs::remove(attach.output_file);
    browser.emplace(attach);
  }
  // The run waits paused for the page's resume: an attach script that fails (it could not
  // start Chromium, or found no viewer) would leave it waiting, so the run is stopped. (It
  // ends with 0 once the page showed the run's end, before the launcher has written the plots.)
  std::optional<int> code;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(20);
  while (!(code = launcher.waitFor(std::chrono::milliseconds(200))) && std::chrono::steady_clock::now() < deadline) {
    if (browser && browser->poll() && *browser->poll() != 0) {
      launcher.signal(SIGTERM);
      code = launcher.waitFor(std::chrono::seconds(30));
      throw std::runtime_error("the browser attached to the " + label + " run ended before the run (exit " +
                               std::to_string(*browser->poll()) + "); see " + attach_log);
    }
  }
  if (browser && !browser->waitFor(std::chrono::seconds(30))) {
    std::fprintf(stderr, "bench e2e: the attached browser did not end with the run\n");
  }
  RunCost cost;
  if (browser) {
    // The attach script measures Chromium's whole process tree over the run it watched.
    std::ifstream log(attach_log);
    for (std::string line; std::getline(log, line);) {
      const auto at = line.find("browser_cpu_s=");
      if (line.rfind("attach:", 0) == 0 && at != std::string::npos) {
        cost.browser_cpu_s = std::strtod(line.c_str() + at + std::string("browser_cpu_s=").size(), nullptr);
        const auto by = line.find("by_type=");
        if (by != std::string::npos) cost.browser_cpu_by_type = line.substr(by + 8, line.find(' ', by) - by - 8);
      }
    }
  }
  cost.label = label;
  cost.launcher_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // A run that ends on a fall (a scenario that ends the run there) measured the steps up to it.
  const bool fell = code && *code == climbsim::kExitFell && fs::exists(run_dir / "summary.json");
  if (!code || (*code != 0 && !fell)) {
    throw std::runtime_error("the " + label + " run failed (exit " + (code ? std::to_string(*code) : "none") +
                             "); see " + spec.output_file);
  }
  const auto summary = readJson(run_dir / "summary.json");
  cost.outcome = summary.value("outcome", "");
  cost.sim_s = summary.at("sim_s").get<double>();
  cost.wall_s = summary.at("wall_s").get<double>();
  cost.rtf = summary.at("realtime_factor").get<double>();
  cost.steps = summary.at("steps").get<double>();
  // The launcher keeps the state of a run under <build>/run/<run name>/state.json; a copy
  // stays beside the run's stats (every process's CPU and context switches).
  const fs::path state_file = fs::path(o.build) / "run" / o.run_name / "state.json";
  std::error_code copy_error;
  fs::copy_file(state_file, run_dir / "launcher_state.json", fs::copy_options::overwrite_existing, copy_error);
  const auto state = readJson(state_file);
  for (const auto& process : state.at("processes")) {
    const std::string name = process.at("name").get<std::string>();
    const std::string service = serviceOf(name);
    if (!process.at("cpu_s").is_null()) {
      cost.cpu_by_service[service] += process.at("cpu_s").get<double>();
      cost.cpu_s += process.at("cpu_s").get<double>();
    }
    if (process.contains("ctx_switches") && !process.at("ctx_switches").is_null()) {
      cost.ctx_by_service[service] += process.at("ctx_switches").get<double>();
      cost.ctx_switches += process.at("ctx_switches").get<double>();
    }
  }
  for (const auto& entry : fs::directory_iterator(stats_dir)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    cost.stats[name] = readJson(entry.path());
    const double d = cost.stats[name].value("deliveries", 0.0);
    cost.deliveries_by_service[serviceOf(name)] += d;
    cost.deliveries += d;
  }
  return cost;
}

/// The raw round trip (climbsim-bench-pingpong, control QoS, two processes) [us], median.
double measureRoundTrip(const Options& o) {
  climbsim::DomainLease lease(200, 230);
  const std::string exe = o.build + "/bin/climbsim-bench-pingpong";
  const std::string domain = std::to_string(lease.id());
  const fs::path dir = fs::path(o.build) / "bench";
  climbsim::ProcessSpec pong_spec;
  pong_spec.argv = {exe, "--role", "pong", "--name", "pong1", "--domain", domain};
  pong_spec.output_file = (dir / "e2e-pong.log").string();
  climbsim::ProcessSpec ping_spec;
  ping_spec.argv = {exe, "--role", "ping", "--pongs", "1", "--domain", domain, "--round-trips", "2000"};
  const fs::path ping_log = dir / "e2e-ping.log";
  fs::remove(ping_log);
  ping_spec.output_file = ping_log.string();
  climbsim::ChildProcess pong(pong_spec);
  climbsim::ChildProcess ping(ping_spec);
  const auto code = ping.waitFor(std::chrono::minutes(2));
  pong.waitFor(std::chrono::seconds(10));
  if (!code || *code != 0) throw std::runtime_error("the round-trip measurement failed; see " + ping_log.string());
  std::ifstream in(ping_log);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find("rtt_us_median=");
    if (line.rfind("pingpong:", 0) == 0 && at != std::string::npos) {
      return std::stod(line.substr(at + std::string("rtt_us_median=").size()));
    }
  }
  throw std::runtime_error("no round trip in " + ping_log.string());
}

/// Sum of counter `key` over the processes of `service`.
double statOf(const RunCost& run, const std::string& service, const std::string& key) {
  double sum = 0;
  for (const auto& [name, stats] : run.stats) {
    if (serviceOf(name) == service) sum += stats.value(key, 0.0);
  }
  return sum;
}

/// Mean of timer `key` per event over the processes of `service` [ms].
double perEventMs(const RunCost& run, const std::string& service, const std::string& key) {
  const double n = statOf(run, service, key + "_n");
  return n > 0 ? 1e3 * statOf(run, service, key) / n : 0.0;
}

/// CPU per computed step of a service's step function [ms].
double stepCpuMs(const RunCost& run, const std::string& service) {
  const double n = statOf(run, service, "steps_computed");
  return n > 0 ? 1e3 * statOf(run, service, "step_cpu_s") / n : 0.0;
}

/// Bytes both ways over this side of the test hosts' veth pair (`deploy/climbsim hosts up`),
/// or nothing without it.
std::optional<double> linkBytes() {
  const fs::path stats = "/sys/class/net/csim-b-here/statistics";
  if (!fs::exists(stats)) return std::nullopt;
  double bytes = 0;
  for (const char* file : {"rx_bytes", "tx_bytes"}) {
    std::ifstream in(stats / file);
    double value = 0;
    in >> value;
    bytes += value;
  }
  return bytes;
}

/// What 2 busy threads get of this machine right now: 2 x the wall time of one thread spinning
/// on arithmetic over the wall time of two at once (2.0 on two free cores, 1.0 when the other
/// builds and runs leave one core). Ratios of parallel work are bounded by it.
double parallelCeiling2() {
  const auto spin = [] {
    volatile double x = 1.0;
    for (long i = 0; i < 60'000'000; ++i) x = x * 1.0000001 + 1e-9;
  };
  const auto timed = [](auto&& work) {
    const auto start = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double one = timed(spin);
  const double two = timed([&] {
    std::thread other(spin);
    spin();
    other.join();
  });
  return 2.0 * one / two;
}

/// Median of `values` (the upper one of an even count); 0 for none.
double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// `bench: e2e-hires:` (sharded sealing): crack-descent-hires (leakage-bound), every service a
/// process on this machine, in three layouts: one renderer of the whole image and one sealing shard
/// (deploy/compose.yaml), one renderer of the sealing's pixels only and one shard
/// (deploy/compose.hires-masked.yaml), and two renderers and two shards
/// (deploy/compose.hires-shards.yaml). --hires-rounds rounds, the layouts' order rotating from
/// round to round; the ratios are medians of the rounds' ratios, and every trace must be the
/// same. With the test hosts up, the bytes per step over the link for
/// deploy/compose.hires-two-hosts.yaml (from a short and a long run, so that discovery cancels).
int runHires(const Options& given) {
  Options o = given;
  o.scenario = "crack-descent-hires";
  o.run_name = "bench-e2e-hires";
  o.sets = {"duration_s=" + std::to_string(o.hires_duration_s)};
  const double ceiling_before = parallelCeiling2();
  struct Layout {
    std::string label, compose;
  };
  const std::vector<Layout> layouts = {
      {"hires-1shard", ""},
      {"hires-1masked", o.root + "/deploy/compose.hires-masked.yaml"},
      {"hires-2shards", o.hires_compose.empty() ? o.root + "/deploy/compose.hires-shards.yaml" : o.hires_compose}};
  const auto trace = [&](const std::string& label) {
    std::ifstream in(fs::path(o.build) / "bench" / ("e2e-" + label) / "trace.csv", std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  std::vector<double> over_whole, over_masked;
  std::vector<RunCost> last(layouts.size());
  bool same = true;
  std::string reference_trace;
  for (int round = 0; round < o.hires_rounds; ++round) {
    std::vector<double> wall(layouts.size(), 0.0);
    for (std::size_t i = 0; i < layouts.size(); ++i) {
      const std::size_t k = (i + static_cast<std::size_t>(round)) % layouts.size();
      Options run_o = o;
      run_o.compose = layouts[k].compose;
      last[k] = runScenario(run_o, layouts[k].label, std::nullopt);
      wall[k] = last[k].wall_s;
      const std::string got = trace(layouts[k].label);
      if (reference_trace.empty()) reference_trace = got;
      same = same && !got.empty() && got == reference_trace;
    }
    over_whole.push_back(wall[0] / wall[2]);
    over_masked.push_back(wall[1] / wall[2]);
    std::printf("bench: e2e-hires: round %d: wall_s %.2f whole image + 1 shard, %.2f masked + 1 shard, %.2f 2 + 2: "
                "ratios %.2f and %.2f\n",
                round + 1, wall[0], wall[1], wall[2], over_whole.back(), over_masked.back());
  }
  const double ceiling_after = parallelCeiling2();
  const RunCost& one = last[0];
  const RunCost& masked = last[1];
  const RunCost& two = last[2];
  const double ratio = median(over_whole), ratio_masked = median(over_masked);
  std::printf("bench: e2e-hires: shard_speedup_2=%.2f (median over %d rounds of wall_s with 1 renderer of the whole "
              "image + 1 shard / wall_s with 2 + 2; last round %.2f / %.2f; %.1f simulated s, 1024 px at 100 Hz; "
              "cores=%u; target >= 1.3) same_trace=%s\n",
              ratio, o.hires_rounds, one.wall_s, two.wall_s, one.sim_s, std::thread::hardware_concurrency(),
              same ? "true" : "false");
  std::printf("bench: e2e-hires: shard_speedup_2_over_masked_1=%.2f (median of wall_s with 1 renderer of the sealing's "
              "pixels + 1 shard, compose.hires-masked.yaml / wall_s with 2 + 2; last round %.2f / %.2f; the "
              "strict comparison: both exchange only the pixels the sealing reads)\n",
              ratio_masked, masked.wall_s, two.wall_s);
  std::printf("bench: e2e-hires: parallel_ceiling_2=%.2f before, %.2f after the runs (2 x wall of 1 spinning thread / "
              "wall of 2 at once: 2.0 on two free cores)\n",
              ceiling_before, ceiling_after);
  const auto cpuOf = [](const RunCost& run, const std::string& service) {
    return run.cpu_by_service.count(service) ? run.cpu_by_service.at(service) : 0.0;
  };
  std::printf("bench: e2e-hires: cpu_s %.2f whole + 1 shard, %.2f masked + 1, %.2f with 2; sealing cpu_s %.2f, %.2f, "
              "%.2f; scene cpu_s %.2f, %.2f, %.2f (last round)\n",
              one.cpu_s, masked.cpu_s, two.cpu_s, cpuOf(one, "sealing"), cpuOf(masked, "sealing"), cpuOf(two, "sealing"),
              cpuOf(one, "scene"), cpuOf(masked, "scene"), cpuOf(two, "scene"));
  // Where the time goes: each service's step CPU per depth frame (the step functions on their
  // main threads; DDS threads and the scene loading left out). Two bounds on the ratio two
  // shards could reach: the wall time with two shards is at least the CPU of all steps shared
  // by the cores (a hard bound, cpu_bound), and about one frame's chain through the loop if its
  // services run one after the other (the slowest renderer, then the slowest shard, then each
  // other service: an estimate, chain_bound).
  const auto frames = [](const RunCost& run) { return std::max(1.0, run.sim_s * 100.0); };  // depth_hz 100
  const auto perFrame = [&](const RunCost& run, const std::string& service, bool slowest) {
    double sum = 0, most = 0;
    for (const auto& [name, stats] : run.stats) {
      if (serviceOf(name) != service) continue;
      const double ms = 1e3 * stats.value("step_cpu_s", 0.0) / frames(run);
      sum += ms;
      most = std::max(most, ms);
    }
    return slowest ? most : sum;
  };
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  json per_frame;
  double all_ms[3] = {0, 0, 0}, chain_ms[3] = {0, 0, 0};
  const char* names[3] = {"one_shard", "one_masked", "two_shards"};
  const char* texts[3] = {"1 shard, whole image", "1 shard, masked", "2 shards"};
  for (int k = 0; k < 3; ++k) {
    const RunCost& run = last[static_cast<std::size_t>(k)];
    std::string line;
    std::set<std::string> services;
    for (const auto& [name, stats] : run.stats) services.insert(serviceOf(name));
    for (const std::string& service : services) {
      const double ms = perFrame(run, service, false);
      all_ms[k] += ms;
      // The recorder and the clock are not in the loop's chain.
      if (service != "recorder" && service != "clock") chain_ms[k] += perFrame(run, service, true);
      char text[64];
      std::snprintf(text, sizeof text, " %s=%.2f", service.c_str(), ms);
      line += text;
      per_frame[names[k]][service] = ms;
    }
    std::printf("bench: e2e-hires: step_cpu_ms_per_frame with %s:%s (all %.2f, chain %.2f; wall %.2f ms per "
                "frame; %.0f deliveries, %.0f context switches per frame)\n",
                texts[k], line.c_str(), all_ms[k], chain_ms[k], 1e3 * run.wall_s / frames(run),
                run.deliveries / frames(run), run.ctx_switches / frames(run));
  }
  const double wall_1_ms = 1e3 * one.wall_s / frames(one);
  const double cpu_bound = wall_1_ms / (all_ms[2] / cores), chain_bound = wall_1_ms / chain_ms[2];
  std::printf("bench: e2e-hires: cpu_bound_2=%.2f (wall %.2f ms per frame with 1 shard / %.2f ms of steps' CPU with 2 "
              "shards over %u cores) chain_bound_2=%.2f (/ %.2f ms chain) measured %.2f (last round)\n",
              cpu_bound, wall_1_ms, all_ms[2] / cores, cores, chain_bound, chain_ms[2], one.wall_s / two.wall_s);
  json out{{"shard_speedup_2", ratio}, {"shard_speedup_2_over_masked_1", ratio_masked},
           {"rounds_over_whole", over_whole}, {"rounds_over_masked", over_masked},
           {"wall_s_1", one.wall_s}, {"wall_s_1_masked", masked.wall_s}, {"wall_s_2", two.wall_s},
           {"same_trace", same}, {"sim_s", one.sim_s}, {"step_cpu_ms_per_frame", per_frame},
           {"parallel_ceiling_2", {ceiling_before, ceiling_after}}, {"cpu_bound_2", cpu_bound}, {"chain_bound_2", chain_bound}};
  if (linkBytes()) {
    Options hosts_o = o;
    hosts_o.compose = o.root + "/deploy/compose.hires-two-hosts.yaml";
    double bytes[2] = {0, 0};
    double steps[2] = {0, 0};
    const double durations[2] = {0.5, o.hires_duration_s};
    for (int k = 0; k < 2; ++k) {
      hosts_o.sets = {"duration_s=" + std::to_string(durations[k])};
      const double before = *linkBytes();
      const RunCost run = runScenario(hosts_o, "hires-two-hosts-" + std::to_string(k), std::nullopt);
      bytes[k] = *linkBytes() - before;
      steps[k] = run.steps;
    }
    const double per_step = (bytes[1] - bytes[0]) / (steps[1] - steps[0]);
    const double image_bytes = 1024.0 * 1024.0 * 4.0;
    std::printf("bench: e2e-hires: two_hosts_bytes_per_step=%.0f (link bytes %.0f over %.0f steps minus %.0f over %.0f; "
                "one whole 1024 px image = %.0f bytes, every 2 steps per shard without tiles)\n",
                per_step, bytes[1], steps[1], bytes[0], steps[0], image_bytes);
    out["two_hosts_bytes_per_step"] = per_step;
  } else {
    std::printf("bench: e2e-hires: two_hosts_bytes_per_step skipped (no test hosts: ./deploy/climbsim hosts up)\n");
  }
  if (!o.out_file.empty()) std::ofstream(o.out_file) << out.dump(2) << '\n';
  return same ? 0 : 1;
}

/// What one run took more than another, service by service (`more` minus `base`, a service
/// missing from `base` counting 0): added to `by_service` (the rounds' values, for medians),
/// as JSON, and as text " scene=+0.12 ..." with `format` (a printf format of one double).
struct ServiceChange {
  json figures;
  std::string text;
};
ServiceChange changeByService(const std::map<std::string, double>& more, const std::map<std::string, double>& base,
                              std::map<std::string, std::vector<double>>& by_service, const char* format = "%+.2f") {
  ServiceChange out;
  out.figures = json::object();
  for (const auto& [service, value] : more) {
    const auto found = base.find(service);
    const double change = value - (found == base.end() ? 0.0 : found->second);
    by_service[service].push_back(change);
    out.figures[service] = change;
    char number[48];
    std::snprintf(number, sizeof(number), format, change);
    out.text += " " + service + "=" + number;
  }
  return out;
}

/// The median of each service's values, as JSON and as text (as changeByService gives them).
ServiceChange medianByService(const std::map<std::string, std::vector<double>>& by_service, const char* format = "%+.2f") {
  ServiceChange out;
  out.figures = json::object();
  for (const auto& [service, values] : by_service) {
    const double m = median(values);
    out.figures[service] = m;
    char number[48];
    std::snprintf(number, sizeof(number), format, m);
    out.text += " " + service + "=" + number;
  }
  return out;
}

/// What run.mcap costs, measured on a shared machine: rounds of two runs one right after the
/// other, one with the recorder writing no run.mcap and one writing it, in alternating order
/// (without first in even rounds, with first in odd ones), so that a change in the machine's
/// load between rounds, or within one, does not count as cost; the median of the rounds' ratios.
struct RecordingCost {
  double cost = 0.0;  ///< median over rounds of realtime_factor without / with, minus 1
  json figures;       ///< the rounds, the reference and the size
};

/// The 1-minute load average (0 if unknown): printed beside each round.
double loadAverage() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : 0.0;
}

RecordingCost measureRecordingCost(const Options& o) {
  fs::create_directories(fs::path(o.build) / "bench");  // the compose variant's folder (run alone: not made yet)
  Options without_o = o;
  without_o.compose = noMcapComposeFile(o);
  std::vector<double> ratios, without_rtfs, with_rtfs, cpu_ratios, recorder_cpu_without, recorder_cpu_with,
      recorder_shares, loads;
  std::map<std::string, std::vector<double>> extra_cpu, extra_ctx;
  const auto recorderCpu = [](const RunCost& run) {
    return run.cpu_by_service.count("recorder") ? run.cpu_by_service.at("recorder") : 0.0;
  };
  json rounds = json::array();
  std::string with_label;
  double sim_s = 0.0;
  for (int round = 0; round < o.recording_rounds; ++round) {
    const double load_before = loadAverage();
    const std::string n = std::to_string(round);
    RunCost without, with;
    if (round % 2 == 0) {
      without = runScenario(without_o, "no-mcap-" + n, std::nullopt);
      with = runScenario(o, "mcap-" + n, std::nullopt);
    } else {
      with = runScenario(o, "mcap-" + n, std::nullopt);
      without = runScenario(without_o, "no-mcap-" + n, std::nullopt);
    }
    with_label = "mcap-" + n;
    sim_s = with.sim_s;
    const double ratio = with.rtf > 0 ? without.rtf / with.rtf : 0.0;
    ratios.push_back(ratio);
    without_rtfs.push_back(without.rtf);
    with_rtfs.push_back(with.rtf);
    // The CPU every process of the run took (its loading included), with over without: what
    // recording costs in work, which another process's load changes far less than the wall time.
    const double cpu_ratio = without.cpu_s > 0 ? with.cpu_s / without.cpu_s : 0.0;
    cpu_ratios.push_back(cpu_ratio);
    recorder_cpu_without.push_back(recorderCpu(without));
    recorder_cpu_with.push_back(recorderCpu(with));
    // The recorder's own extra CPU over the whole run's CPU without run.mcap: the work recording
    // adds where it is done, free of the other processes' noise (their waits, their wake-ups).
    const double recorder_share = without.cpu_s > 0 ? (recorderCpu(with) - recorderCpu(without)) / without.cpu_s : 0.0;
    recorder_shares.push_back(recorder_share);
    const double load_after = loadAverage();
    loads.push_back(0.5 * (load_before + load_after));
    // Where the run with run.mcap took more, process by process: the recorder's own work, or
    // the others' (their waits and wake-ups show in the context switches).
    const ServiceChange cpu_change = changeByService(with.cpu_by_service, without.cpu_by_service, extra_cpu);
    const ServiceChange ctx_change = changeByService(with.ctx_by_service, without.ctx_by_service, extra_ctx, "%+.0f");
    std::printf("bench: e2e: recording round %d (%s first): realtime_factor %.2f without run.mcap, %.2f with it: "
                "without/with %.3f, cost %.1f%%; cpu_s %.2f without, %.2f with (recorder %.2f, %.2f): cpu cost %.1f%%, "
                "recorder's extra cpu %.1f%% of the run's; extra cpu_s by service%s; extra context switches by "
                "service%s (load average %.2f before, %.2f after, %u cores)\n",
                round + 1, round % 2 == 0 ? "without" : "with", without.rtf, with.rtf, ratio, 100.0 * (ratio - 1.0),
                without.cpu_s, with.cpu_s, recorderCpu(without), recorderCpu(with), 100.0 * (cpu_ratio - 1.0),
                100.0 * recorder_share, cpu_change.text.c_str(), ctx_change.text.c_str(), load_before, load_after,
                std::thread::hardware_concurrency());
    rounds.push_back({{"without_first", round % 2 == 0}, {"realtime_factor_without_mcap", without.rtf},
                      {"realtime_factor_with_mcap", with.rtf}, {"without_over_with", ratio},
                      {"cpu_s_without_mcap", without.cpu_s}, {"cpu_s_with_mcap", with.cpu_s},
                      {"recorder_cpu_s_without_mcap", recorderCpu(without)}, {"recorder_cpu_s_with_mcap", recorderCpu(with)},
                      {"recorder_extra_cpu_share", recorder_share}, {"extra_cpu_s_by_service", cpu_change.figures},
                      {"extra_ctx_switches_by_service", ctx_change.figures},
                      {"loadavg_before", load_before}, {"loadavg_after", load_after}});
  }
  RecordingCost out;
  const fs::path mcap_file = fs::path(o.build) / "bench" / ("e2e-" + with_label) / "run.mcap";
  const double mcap_bytes = !with_label.empty() && fs::exists(mcap_file) ? static_cast<double>(fs::file_size(mcap_file)) : 0.0;
  const double mcap_bytes_per_sim_s = sim_s > 0 ? mcap_bytes / sim_s : 0.0;
  out.cost = ratios.empty() ? 0.0 : median(ratios) - 1.0;
  const double rtf_without = without_rtfs.empty() ? 0.0 : median(without_rtfs);
  const double rtf_with = with_rtfs.empty() ? 0.0 : median(with_rtfs);
  const double cpu_cost = cpu_ratios.empty() ? 0.0 : median(cpu_ratios) - 1.0;
  const double recorder_cpu_cost = recorder_shares.empty() ? 0.0 : median(recorder_shares);
  const double load = loads.empty() ? 0.0 : median(loads);
  const ServiceChange cpu_medians = medianByService(extra_cpu);
  const ServiceChange ctx_medians = medianByService(extra_ctx, "%+.0f");
  const auto [lowest, highest] = ratios.empty() ? std::pair<double, double>{0.0, 0.0}
                                                : std::pair<double, double>{*std::min_element(ratios.begin(), ratios.end()),
                                                                            *std::max_element(ratios.begin(), ratios.end())};
  std::printf("bench: e2e: recording recording_cost=%.1f%% (median over %zu rounds of realtime_factor without run.mcap "
              "/ with it in the same round, minus 1; the rounds' ratios %.3f..%.3f; target <= 3%%) reference: "
              "realtime_factor_without_mcap=%.2f realtime_factor_with_mcap=%.2f (medians) recording_cpu_cost=%.1f%% "
              "(median of cpu_s with / without, minus 1; recorder cpu_s %.2f without, %.2f with, medians) "
              "recorder_extra_cpu_share=%.1f%% (median of the recorder's cpu_s with minus without over the run's cpu_s "
              "without) extra cpu_s by service (medians)%s extra context switches by service (medians)%s "
              "mcap_bytes_per_sim_s=%.0f mcap_bytes=%.0f sim_s=%g (target: %s's whole run <= 50 MB) "
              "load_average=%.2f (median of the rounds') cores=%u\n",
              100.0 * out.cost, ratios.size(), lowest, highest, rtf_without, rtf_with, 100.0 * cpu_cost,
              recorder_cpu_without.empty() ? 0.0 : median(recorder_cpu_without),
              recorder_cpu_with.empty() ? 0.0 : median(recorder_cpu_with), 100.0 * recorder_cpu_cost,
              cpu_medians.text.c_str(), ctx_medians.text.c_str(), mcap_bytes_per_sim_s, mcap_bytes, sim_s,
              o.scenario.c_str(), load, std::thread::hardware_concurrency());
  out.figures = {{"recording_cost", out.cost}, {"rounds", rounds}, {"realtime_factor_without_mcap", rtf_without},
              {"realtime_factor_with_mcap", rtf_with}, {"recording_cpu_cost", cpu_cost},
              {"recorder_cpu_s_without_mcap", recorder_cpu_without.empty() ? 0.0 : median(recorder_cpu_without)},
              {"recorder_cpu_s_with_mcap", recorder_cpu_with.empty() ? 0.0 : median(recorder_cpu_with)},
              {"recorder_extra_cpu_share", recorder_cpu_cost}, {"extra_cpu_s_by_service", cpu_medians.figures},
              {"extra_ctx_switches_by_service", ctx_medians.figures}, {"loadavg_median", load},
              {"mcap_bytes_per_sim_s", mcap_bytes_per_sim_s},
              {"mcap_bytes", mcap_bytes}, {"cores", std::thread::hardware_concurrency()}};
  return out;
}

/// --recording-only: the recording rounds alone, into --out as {"scenario", "recording"}.
int runRecordingOnly(const Options& o) {
  const RecordingCost recording = measureRecordingCost(o);
  if (!o.out_file.empty()) {
    // The load the rounds ran under: the mean of the 1-minute load averages around them (the
    // benchmark table's line for rows rewritten alone).
    double load = 0.0;
    const auto& rounds = recording.figures.at("rounds");
    for (const auto& r : rounds) load += 0.5 * (r.at("loadavg_before").get<double>() + r.at("loadavg_after").get<double>());
    json doc{{"scenario", o.scenario}, {"recording", recording.figures}};
    if (!rounds.empty()) doc["loadavg"] = load / static_cast<double>(rounds.size());
    std::ofstream(o.out_file) << doc.dump(2) << "\n";
  }
  return 0;
}

/// The crack scenario of a shipped robot: crack-descent for CROMSCI, crack-<robot> for the others.
std::string crackScenarioOf(const std::string& robot) { return robot == "cromsci" ? "crack-descent" : "crack-" + robot; }

/// The robots `--robot` names (every shipped one for "all"), CROMSCI first: it is the reference.
std::vector<std::string> comparedRobots(const Options& o) {
  const std::vector<std::string> shipped = climbsim::shippedRobotNames();
  std::vector<std::string> names{"cromsci"};
  if (o.robot == "all") {
    for (const auto& name : shipped) {
      if (name != "cromsci") names.push_back(name);
    }
  } else if (o.robot != "cromsci" && o.robot != "none") {
    if (std::find(shipped.begin(), shipped.end(), o.robot) == shipped.end()) {
      std::string known;
      for (const auto& name : shipped) known += (known.empty() ? "" : ", ") + name;
      throw climbsim::ConfigError("--robot = '" + o.robot + "': not a shipped robot (" + known + ", all or none)");
    }
    names.push_back(o.robot);
  }
  return names;
}

/// One robot of the comparison: its crack scenario's runs, round by round.
struct RobotRuns {
  std::string robot, scenario;
  std::string skipped;                  ///< why it was not run ("" when it was)
  std::vector<double> rtf, deliveries_per_step, over_cromsci;  ///< per round
  std::string outcome;                  ///< of the last run (completed, fell, ...)
  double sim_s = 0.0;                   ///< simulated seconds of the last run (a fall ends it)
};

/// `--robot`: each robot's crack scenario beside CROMSCI's crack-descent, every service a
/// process at the default W, in --robot-rounds rounds run back to back (the order rotating
/// from round to round). Per robot: the median over the rounds of its realtime_factor, of its
/// deliveries per step and of rtf_over_cromsci, its realtime_factor / CROMSCI's in the same
/// round. A robot without a crack scenario is skipped with a line saying so.
json compareRobots(const Options& o) {
  std::vector<RobotRuns> robots;
  for (const auto& name : comparedRobots(o)) {
    RobotRuns r;
    r.robot = name;
    r.scenario = crackScenarioOf(name);
    const fs::path file = fs::path(o.root) / "deploy" / "scenarios" / (r.scenario + ".yaml");
    if (!fs::exists(file)) r.skipped = "no crack scenario (deploy/scenarios/" + r.scenario + ".yaml)";
    robots.push_back(r);
  }
  if (!robots.front().skipped.empty()) throw std::runtime_error("cromsci: " + robots.front().skipped);
  std::vector<std::size_t> ran;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    if (robots[i].skipped.empty()) ran.push_back(i);
  }
  for (int round = 0; round < o.robot_rounds; ++round) {
    for (std::size_t i = 0; i < ran.size(); ++i) {
      RobotRuns& r = robots[ran[(i + static_cast<std::size_t>(round)) % ran.size()]];
      Options run_o = o;
      run_o.scenario = r.scenario;
      const RunCost cost = runScenario(run_o, "robot-" + r.robot, std::nullopt);
      r.rtf.push_back(cost.rtf);
      r.deliveries_per_step.push_back(cost.steps > 0 ? cost.deliveries / cost.steps : 0.0);
      r.outcome = cost.outcome;
      r.sim_s = cost.sim_s;
    }
    std::string line;
    for (const std::size_t i : ran) {
      RobotRuns& r = robots[i];
      r.over_cromsci.push_back(robots.front().rtf.back() > 0 ? r.rtf.back() / robots.front().rtf.back() : 0.0);
      char text[128];
      std::snprintf(text, sizeof text, " %s=%.2f (%.3f)", r.robot.c_str(), r.rtf.back(), r.over_cromsci.back());
      line += text;
    }
    std::printf("bench: e2e: robots round %d: realtime_factor (over cromsci's):%s\n", round + 1, line.c_str());
  }
  const RobotRuns& cromsci = robots.front();
  json entries = json::array();
  for (const RobotRuns& r : robots) {
    if (!r.skipped.empty()) {
      std::printf("bench: e2e: robot=%s skipped: %s\n", r.robot.c_str(), r.skipped.c_str());
      entries.push_back({{"robot", r.robot}, {"scenario", r.scenario}, {"skipped", r.skipped}});
      continue;
    }
    const double rtf = median(r.rtf), deliveries = median(r.deliveries_per_step), over = median(r.over_cromsci);
    if (&r == &cromsci) {
      std::printf("bench: e2e: robot=cromsci scenario=%s realtime_factor=%.2f deliveries_per_step=%.2f (median of %d "
                  "rounds at the default W; the reference of rtf_over_cromsci) outcome=%s sim_s=%.2f\n",
                  r.scenario.c_str(), rtf, deliveries, o.robot_rounds, r.outcome.c_str(), r.sim_s);
    } else {
      std::printf("bench: e2e: robot=%s scenario=%s realtime_factor=%.2f deliveries_per_step=%.2f rtf_over_cromsci=%.3f "
                  "(median of %d rounds of realtime_factor / cromsci's on %s in the same round; cromsci "
                  "realtime_factor=%.2f deliveries_per_step=%.2f) outcome=%s sim_s=%.2f target=%g met=%s\n",
                  r.robot.c_str(), r.scenario.c_str(), rtf, deliveries, over, o.robot_rounds, cromsci.scenario.c_str(),
                  median(cromsci.rtf), median(cromsci.deliveries_per_step), r.outcome.c_str(), r.sim_s,
                  o.robot_target, over >= o.robot_target ? "true" : "false");
    }
    entries.push_back({{"robot", r.robot}, {"scenario", r.scenario}, {"realtime_factor", rtf},
                       {"deliveries_per_step", deliveries}, {"rtf_over_cromsci", over},
                       {"outcome", r.outcome}, {"sim_s", r.sim_s},
                       {"rounds_realtime_factor", r.rtf}, {"rounds_rtf_over_cromsci", r.over_cromsci}});
  }
  return {{"rounds", o.robot_rounds}, {"target_rtf_over_cromsci", o.robot_target}, {"robots", entries}};
}

/// `--robots-only`: the robots' comparison alone, CROMSCI's figures of it as the run's
/// realtime_factor and deliveries_per_step.
int runRobotsOnly(const Options& o) {
  const json robots = compareRobots(o);
  const json& cromsci = robots.at("robots").at(0);
  std::printf("bench: e2e: scenario=%s realtime_factor=%.2f deliveries_per_step=%.2f (cromsci, median of %d runs at "
              "the default W; --robots-only: no W = 1, viewer, recording, security or solo runs)\n",
              cromsci.at("scenario").get<std::string>().c_str(), cromsci.at("realtime_factor").get<double>(),
              cromsci.at("deliveries_per_step").get<double>(), o.robot_rounds);
  if (!o.out_file.empty()) {
    const json doc = {{"scenario", cromsci.at("scenario")},
                      {"realtime_factor", cromsci.at("realtime_factor")},
                      {"deliveries_per_step", cromsci.at("deliveries_per_step")},
                      {"robots_only", true},
                      {"robots", robots}};
    std::ofstream(o.out_file) << doc.dump(2) << "\n";
  }
  return 0;
}

/// What DDS Security costs, measured on a shared machine as the recording is: rounds of an
/// unsecured run and a secured one (`run --secure`) one right after the other, in alternating
/// order, the median of the rounds' ratios of realtime_factor and of the CPU every process took
/// (the CPU is what another process's load changes least). Each round says the load average and
/// where the secured run's extra CPU went, service by service; the secured trace must equal the
/// unsecured one byte for byte (same_trace).
json measureSecurityCost(const Options& o) {
  std::vector<double> costs, cpu_costs, rtfs, rtfs_secured, cpus, cpus_secured;
  std::map<std::string, std::vector<double>> extra_by_service;
  json rounds = json::array();
  bool same = true;
  const auto trace = [&](const std::string& label) {
    std::ifstream in(fs::path(o.build) / "bench" / ("e2e-" + label) / "trace.csv", std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (int round = 0; round < o.security_rounds; ++round) {
    const double load_before = loadAverage();
    const std::string n = std::to_string(round);
    const bool unsecured_first = round % 2 == 0;
    RunCost open, secured;
    if (unsecured_first) open = runScenario(o, "unsecured-" + n, std::nullopt);
    secured = runScenario(o, "secured-" + n, std::nullopt, false, true, true);
    if (!unsecured_first) open = runScenario(o, "unsecured-" + n, std::nullopt);
    const double load_after = loadAverage();
    const bool round_same = trace("secured-" + n) == trace("unsecured-" + n);
    same = same && round_same;
    const double cost = open.rtf > 0 ? 1.0 - secured.rtf / open.rtf : 0.0;
    const double cpu_cost = open.cpu_s > 0 ? secured.cpu_s / open.cpu_s - 1.0 : 0.0;
    costs.push_back(cost);
    cpu_costs.push_back(cpu_cost);
    rtfs.push_back(open.rtf);
    rtfs_secured.push_back(secured.rtf);
    cpus.push_back(open.cpu_s);
    cpus_secured.push_back(secured.cpu_s);
    const ServiceChange extra = changeByService(secured.cpu_by_service, open.cpu_by_service, extra_by_service);
    std::printf("bench: e2e: security round %d (%s first): realtime_factor %.2f unsecured, %.2f secured: cost %.1f%%; "
                "cpu_s %.2f unsecured, %.2f secured: cpu cost %.1f%%; extra cpu_s by service%s; same_trace=%s "
                "(load average %.2f before, %.2f after, %u cores)\n",
                round + 1, unsecured_first ? "unsecured" : "secured", open.rtf, secured.rtf, 100.0 * cost, open.cpu_s,
                secured.cpu_s, 100.0 * cpu_cost, extra.text.c_str(), round_same ? "true" : "false", load_before,
                load_after, std::thread::hardware_concurrency());
    rounds.push_back({{"unsecured_first", unsecured_first}, {"realtime_factor", open.rtf},
                      {"realtime_factor_secured", secured.rtf}, {"security_cost", cost}, {"cpu_s", open.cpu_s},
                      {"cpu_s_secured", secured.cpu_s}, {"security_cpu_cost", cpu_cost},
                      {"extra_cpu_s_by_service", extra.figures}, {"same_trace", round_same},
                      {"loadavg_before", load_before}, {"loadavg_after", load_after}});
  }
  if (costs.empty()) return json();
  const double cost = median(costs);
  const double cpu_cost = median(cpu_costs);
  const ServiceChange extra = medianByService(extra_by_service);
  std::printf("bench: e2e: security realtime_factor_secured=%.2f realtime_factor=%.2f secured_over_unsecured=%.3f "
              "security_cost=%.1f%% (median over %zu rounds of 1 - realtime_factor secured / unsecured in the same "
              "round; the rounds' costs %.1f..%.1f%%; target <= 20%%) security_cpu_cost=%.1f%% (median of cpu_s "
              "secured / unsecured, minus 1) reference: cpu_s_secured=%.2f cpu_s=%.2f (medians) extra cpu_s by "
              "service (medians)%s same_trace=%s met=%s\n",
              median(rtfs_secured), median(rtfs), 1.0 - cost, 100.0 * cost, costs.size(),
              100.0 * *std::min_element(costs.begin(), costs.end()), 100.0 * *std::max_element(costs.begin(), costs.end()),
              100.0 * cpu_cost, median(cpus_secured), median(cpus), extra.text.c_str(), same ? "true" : "false",
              cost <= 0.20 ? "true" : "false");
  return {{"realtime_factor_secured", median(rtfs_secured)}, {"realtime_factor", median(rtfs)},
          {"secured_over_unsecured", 1.0 - cost}, {"security_cost", cost}, {"security_cpu_cost", cpu_cost},
          {"cpu_s_secured", median(cpus_secured)}, {"cpu_s", median(cpus)},
          {"extra_cpu_s_by_service", extra.figures}, {"rounds", rounds}, {"same_trace", same}, {"target_cost", 0.20}};
}

/// --security-only: the security rounds alone, into --out as {"scenario", "security", "loadavg"}.
int runSecurityOnly(const Options& o) {
  const json security = measureSecurityCost(o);
  if (!o.out_file.empty()) {
    double load = 0.0;
    const auto& rounds = security.at("rounds");
    for (const auto& r : rounds) load += 0.5 * (r.at("loadavg_before").get<double>() + r.at("loadavg_after").get<double>());
    json doc{{"scenario", o.scenario}, {"security", security}};
    if (!rounds.empty()) doc["loadavg"] = load / static_cast<double>(rounds.size());
    std::ofstream(o.out_file) << doc.dump(2) << "\n";
  }
  return 0;
}

int run(const Options& o) {
  const double rtt_us = measureRoundTrip(o);
  const RunCost w1 = runScenario(o, "w1", 1);
  const RunCost wd = runScenario(o, "default", std::nullopt);
  std::optional<RunCost> wv, ws;
  // The viewer's cost: pairs of runs, one without and one with the viewer and a page, one
  // right after the other, so that a change in the machine's load between pairs does not
  // count as cost; the median pair is reported (single runs here vary by +-20 %).
  std::vector<double> viewer_costs;
  if (o.viewer) {
    for (int round = 0; round < o.viewer_rounds; ++round) {
      const RunCost without = round == 0 ? wd : runScenario(o, "default-" + std::to_string(round), std::nullopt);
      wv = runScenario(o, "viewer", std::nullopt, true);
      viewer_costs.push_back(without.rtf > 0 ? 1.0 - wv->rtf / without.rtf : 0.0);
      std::printf("bench: e2e: viewer round %d: realtime_factor %.2f without, %.2f with the viewer and a page: "
                  "cost %.1f%% (browser_cpu_s %.2f [%s], viewer_cpu_s %.2f)\n",
                  round + 1, without.rtf, wv->rtf, 100.0 * viewer_costs.back(), wv->browser_cpu_s,
                  wv->browser_cpu_by_type.c_str(),
                  wv->cpu_by_service.count("viewer") ? wv->cpu_by_service.at("viewer") : 0.0);
    }
    ws = runScenario(o, "viewer-service", std::nullopt, true, false);
  }
  const RecordingCost recording = measureRecordingCost(o);
  const json security = o.secure ? measureSecurityCost(o) : json();
  // The speed limit: the same models in one process on one core, no messages at all.
  const climbsim::bench::SoloCost solo = climbsim::bench::runSoloPinned(o.build, o.scenario, "e2e-solo");
  const double distributed_over_solo = solo.realtime_factor > 0 ? wd.rtf / solo.realtime_factor : 0.0;
  const double speedup = w1.rtf > 0 ? wd.rtf / w1.rtf : 0.0;
  const double steps = wd.steps;
  const double step_us = steps > 0 ? 1e6 * wd.wall_s / steps : 0.0;
  const double step_over_rtt = rtt_us > 0 ? step_us / rtt_us : 0.0;
  const double deliveries_per_step = steps > 0 ? wd.deliveries / steps : 0.0;
  const double ctx_per_step = steps > 0 ? wd.ctx_switches / steps : 0.0;
  const double w1_deliveries_per_step = w1.steps > 0 ? w1.deliveries / w1.steps : 0.0;
  const double w1_ctx_per_step = w1.steps > 0 ? w1.ctx_switches / w1.steps : 0.0;
  const bool met = wd.rtf >= o.target && step_over_rtt <= o.step_over_rtt_target && speedup >= o.speedup_target;

  std::printf("bench: e2e: scenario=%s realtime_factor=%.2f realtime_factor_w1=%.2f speedup_vs_w1=%.2f "
              "deliveries_per_step=%.2f ctx_switches_per_step=%.1f rtt_us=%.1f step_over_rtt=%.2f step_us=%.1f "
              "steps=%.0f sim_s=%g wall_s=%.3f wall_s_w1=%.3f target_rtf=%g target_step_over_rtt=%g "
              "target_speedup=%g met=%s\n",
              o.scenario.c_str(), wd.rtf, w1.rtf, speedup, deliveries_per_step, ctx_per_step, rtt_us, step_over_rtt,
              step_us, steps, wd.sim_s, wd.wall_s, w1.wall_s, o.target, o.step_over_rtt_target, o.speedup_target,
              met ? "true" : "false");
  if (wv) {
    // The viewer may cost at most 5 %; both runs at the default window. The cost is
    // the median over the rounds; the other figures are of the last viewer run.
    const double cost = median(viewer_costs);
    // Where it goes: the viewer's own deliveries and CPU, the browser's CPU, and the
    // deliveries per step of the whole run with the viewer beside those without it.
    const double viewer_deliveries = wv->deliveries_by_service.count("viewer") ? wv->deliveries_by_service.at("viewer") : 0.0;
    std::printf("bench: e2e: viewer realtime_factor_viewer=%.2f realtime_factor=%.2f viewer_cost=%.1f%% (median of %zu "
                "pairs) "
                "viewer_cpu_s=%.2f browser_cpu_s=%.2f cpu_s_viewer_run=%.2f cpu_s=%.2f viewer_deliveries_per_step=%.3f "
                "deliveries_per_step_viewer_run=%.2f deliveries_per_step=%.2f target_cost=5%% met=%s\n",
                wv->rtf, wd.rtf, 100.0 * cost, viewer_costs.size(),
                wv->cpu_by_service.count("viewer") ? wv->cpu_by_service.at("viewer") : 0.0, wv->browser_cpu_s,
                wv->cpu_s, wd.cpu_s, wv->steps > 0 ? viewer_deliveries / wv->steps : 0.0,
                wv->steps > 0 ? wv->deliveries / wv->steps : 0.0, deliveries_per_step, cost <= 0.05 ? "true" : "false");
    // Less noisy than the cost: the CPU the viewer and the page took, as a share of what the
    // machine's cores offered over the viewer run (what they take from a run that keeps every
    // core busy).
    const double observer_cpu_s =
        (wv->cpu_by_service.count("viewer") ? wv->cpu_by_service.at("viewer") : 0.0) + wv->browser_cpu_s;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    std::printf("bench: e2e: viewer observer_cpu_share=%.1f%% (viewer + browser cpu_s %.2f over wall_s %.3f x %u cores)\n",
                100.0 * observer_cpu_s / (wv->wall_s * cores), observer_cpu_s, wv->wall_s, cores);
  }
  if (ws) {
    const double cost = wd.rtf > 0 ? 1.0 - ws->rtf / wd.rtf : 0.0;
    std::printf("bench: e2e: viewer_service (no page attached) realtime_factor_viewer_service=%.2f realtime_factor=%.2f "
                "viewer_service_cost=%.1f%% viewer_cpu_s=%.2f\n",
                ws->rtf, wd.rtf, 100.0 * cost,
                ws->cpu_by_service.count("viewer") ? ws->cpu_by_service.at("viewer") : 0.0);
  }
  // The goal is >= 1.0: the distributed run has two cores against the solo run's one.
  std::printf("bench: e2e: distributed_over_solo=%.2f realtime_factor=%.2f realtime_factor_solo=%.2f "
              "(solo: one process, one core, no DDS; wall_s=%.3f, distributed wall_s=%.3f) target=1.0 met=%s\n",
              distributed_over_solo, wd.rtf, solo.realtime_factor, solo.wall_s, wd.wall_s,
              distributed_over_solo >= 1.0 ? "true" : "false");
  std::printf("bench: e2e: w1 deliveries_per_step=%.2f ctx_switches_per_step=%.1f cpu_s=%.2f; default cpu_s=%.2f "
              "cpu_s_over_w1=%.2f\n",
              w1_deliveries_per_step, w1_ctx_per_step, w1.cpu_s, wd.cpu_s, w1.cpu_s > 0 ? wd.cpu_s / w1.cpu_s : 0.0);

  // Per depth frame, from the default run: the scene renders and publishes, the sealing
  // receives (take, deserialise, copies: CPU of its thread, not its waiting) and computes.
  const double render_ms = perEventMs(wd, "scene", "depth_render_s");
  const double publish_ms = perEventMs(wd, "scene", "depth_publish_cpu_s");
  const double receive_ms = perEventMs(wd, "sealing", "depth_receive_cpu_s");
  const double model_ms = perEventMs(wd, "sealing", "sealing_model_s");
  const double frames = statOf(wd, "scene", "depth_render_s_n");
  std::printf("bench: e2e: depth_frame_ms render=%.3f publish_cpu=%.3f receive_cpu=%.3f transport=%.3f "
              "sealing_model=%.3f frames=%.0f\n",
              render_ms, publish_ms, receive_ms, publish_ms + receive_ms, model_ms, frames);

  // The tightest loop: scene (4m) -> sealing (4m+1) -> thermo (4m+2) -> drive (4m+3) -> scene
  // (4m+4) carries 4 steps of lag, so steps/s <= 4 / (its four steps + 4 one-way latencies).
  const double scene_ms = stepCpuMs(wd, "scene");
  const double sealing_ms = stepCpuMs(wd, "sealing");
  const double thermo_ms = stepCpuMs(wd, "thermo");
  const double drive_ms = stepCpuMs(wd, "drive");
  const double loop_ms = scene_ms + sealing_ms + thermo_ms + drive_ms + 2.0 * rtt_us * 1e-3;
  const double dt_s = steps > 0 ? wd.sim_s / steps : 0.0;
  const double loop_bound_rtf = loop_ms > 0 ? 4.0 * dt_s / (loop_ms * 1e-3) : 0.0;
  std::printf("bench: e2e: loop_bound scene_step_ms=%.3f sealing_step_ms=%.3f thermo_step_ms=%.3f "
              "drive_step_ms=%.3f four_one_way_ms=%.3f loop_ms=%.3f loop_bound_rtf=%.2f (measured %.2f: %s)\n",
              scene_ms, sealing_ms, thermo_ms, drive_ms, 2.0 * rtt_us * 1e-3, loop_ms, loop_bound_rtf, wd.rtf,
              wd.rtf >= 0.8 * loop_bound_rtf ? "the loop is the limit" : "below the loop bound");
  // Two bounds on the distributed run: the loop's latency (above) and the machine's CPU, what
  // every roster member's process (all its threads) took from its first step to its end shared
  // by the cores (sim_s x cores / run_cpu_s). The lower one is what limits.
  const unsigned bench_cores = std::max(1u, std::thread::hardware_concurrency());
  double run_cpu_s = 0.0;
  for (const auto& [service, cpu] : wd.cpu_by_service) run_cpu_s += statOf(wd, service, "run_cpu_s");
  const double cpu_bound_rtf = run_cpu_s > 0 ? wd.sim_s * bench_cores / run_cpu_s : 0.0;
  const double rtf_over_loop_bound = loop_bound_rtf > 0 ? wd.rtf / loop_bound_rtf : 0.0;
  const double rtf_over_cpu_bound = cpu_bound_rtf > 0 ? wd.rtf / cpu_bound_rtf : 0.0;
  char security_text[96] = "not measured (--secure measures it)";
  if (!security.is_null()) {
    std::snprintf(security_text, sizeof security_text, "%.1f%% (reference: the unsecured rounds' realtime_factor)",
                  100.0 * security.at("security_cost").get<double>());
  }
  std::printf("bench: e2e: speed render_ms=%.3f sealing_step_ms=%.3f drive_step_ms=%.3f (CPU per depth frame and per "
              "loop step, reference: the default run's %.0f frames) loop_bound_rtf=%.2f (reference: loop_ms=%.3f per "
              "4 steps of %.1f ms) realtime_factor=%.2f realtime_factor_solo=%.2f (reference: sim_s=%.3f) "
              "rtf_over_loop_bound=%.2f (target >= 0.8) cpu_bound_rtf=%.2f (reference: run_cpu_s=%.2f of every roster "
              "member from its first step, over %u cores) rtf_over_cpu_bound=%.2f security_cost=%s\n",
              render_ms, sealing_ms, drive_ms, frames, loop_bound_rtf, loop_ms, dt_s * 1e3, wd.rtf,
              solo.realtime_factor, wd.sim_s, rtf_over_loop_bound, cpu_bound_rtf, run_cpu_s, bench_cores,
              rtf_over_cpu_bound,
              security_text);

  std::ostringstream per_service;
  json services;
  for (const auto& [service, cpu] : wd.cpu_by_service) {
    const double d = wd.deliveries_by_service.count(service) ? wd.deliveries_by_service.at(service) : 0.0;
    const double c = wd.ctx_by_service.count(service) ? wd.ctx_by_service.at(service) : 0.0;
    char text[128];
    std::snprintf(text, sizeof(text), " %s=%.2f/%.1f", service.c_str(), d / steps, c / steps);
    per_service << text;
    services[service] = {{"cpu_s", cpu},
                         {"share_percent", wd.cpu_s > 0 ? 100.0 * cpu / wd.cpu_s : 0.0},
                         {"deliveries_per_step", d / steps},
                         {"ctx_switches_per_step", c / steps},
                         {"step_cpu_ms", stepCpuMs(wd, service)}};
  }
  std::printf("bench: e2e: per_step deliveries/ctx_switches%s\n", per_service.str().c_str());
  std::ostringstream shares;
  for (const auto& [service, cpu] : wd.cpu_by_service) {
    char text[96];
    std::snprintf(text, sizeof(text), " %s=%.1f%%", service.c_str(), wd.cpu_s > 0 ? 100.0 * cpu / wd.cpu_s : 0.0);
    shares << text;
  }
  std::printf("bench: e2e: cpu_share%s (of cpu_s=%.2f; launcher_wall_s=%.2f incl. scene loading)\n",
              shares.str().c_str(), wd.cpu_s, wd.launcher_wall_s);
  const json robots = o.robot == "none" ? json() : compareRobots(o);
  if (!o.out_file.empty()) {
    json doc = {{"scenario", o.scenario},
                {"realtime_factor", wd.rtf},
                {"realtime_factor_w1", w1.rtf},
                {"speedup_vs_w1", speedup},
                {"deliveries_per_step", deliveries_per_step},
                {"ctx_switches_per_step", ctx_per_step},
                {"rtt_us", rtt_us},
                {"step_over_rtt", step_over_rtt},
                {"step_us", step_us},
                {"steps", steps},
                {"sim_s", wd.sim_s},
                {"wall_s", wd.wall_s},
                {"wall_s_w1", w1.wall_s},
                {"w1", {{"deliveries_per_step", w1_deliveries_per_step}, {"ctx_switches_per_step", w1_ctx_per_step},
                        {"cpu_s", w1.cpu_s}}},
                {"cpu_s", wd.cpu_s},
                {"launcher_wall_s", wd.launcher_wall_s},
                {"recording", recording.figures},
                {"depth_frame_ms",
                 {{"render", render_ms}, {"publish_cpu", publish_ms}, {"receive_cpu", receive_ms},
                  {"transport", publish_ms + receive_ms}, {"sealing_model", model_ms}}},
                {"loop_bound",
                 {{"scene_step_ms", scene_ms}, {"sealing_step_ms", sealing_ms}, {"thermo_step_ms", thermo_ms},
                  {"drive_step_ms", drive_ms}, {"loop_ms", loop_ms}, {"realtime_factor", loop_bound_rtf}}},
                {"rtf_over_loop_bound", rtf_over_loop_bound},
                {"cpu_bound", {{"realtime_factor", cpu_bound_rtf}, {"run_cpu_s", run_cpu_s}, {"cores", bench_cores}}},
                {"rtf_over_cpu_bound", rtf_over_cpu_bound},
                {"targets",
                 {{"realtime_factor", o.target}, {"step_over_rtt", o.step_over_rtt_target},
                  {"speedup_vs_w1", o.speedup_target}}},
                {"met", met},
                {"solo", {{"realtime_factor", solo.realtime_factor}, {"wall_s", solo.wall_s}, {"cpu_s", solo.cpu_s}}},
                {"distributed_over_solo", distributed_over_solo},
                {"viewer", wv ? json{{"realtime_factor", wv->rtf},
                                     {"cost", median(viewer_costs)},
                                     {"costs", viewer_costs},
                                     {"cpu_s", wv->cpu_by_service.count("viewer") ? wv->cpu_by_service.at("viewer") : 0.0},
                                     {"browser_cpu_s", wv->browser_cpu_s},
                                     {"realtime_factor_service_only", ws ? ws->rtf : 0.0}}
                              : json()},
                {"security", security},
                {"robots", robots},
                {"services", services}};
    // Without recording rounds nothing was measured: no figures (the table keeps its rows).
    if (o.recording_rounds == 0) doc.erase("recording");
    std::ofstream(o.out_file) << doc.dump(2) << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-e2e: the whole closed loop at W = 1 and the default window, and what a step costs"};
  Options options;
  app.add_option("--out", options.out_file, "JSON file to write");
  app.add_option("--root", options.root, "the climbsim checkout");
  app.add_option("--build", options.build, "the build directory");
  app.add_option("--scenario", options.scenario, "scenario name or file (deploy/compose.yaml runs it)");
  app.add_option("--set", options.sets, "scenario override for every run (`run --set`), repeatable");
  app.add_option("--target", options.target, "real-time factor to reach");
  app.add_flag("!--no-viewer", options.viewer, "skip the run with the viewer and a headless browser attached");
  app.add_option("--viewer-rounds", options.viewer_rounds, "pairs of runs without/with the viewer (median cost)")
      ->check(CLI::Range(1, 20));
  app.add_option("--recording-rounds", options.recording_rounds,
                 "rounds of a run without and one with run.mcap, in alternating order (median recording_cost; 0: none)")
      ->check(CLI::Range(0, 20));
  app.add_flag("--recording-only", options.recording_only,
               "only the recording rounds (recording_cost and run.mcap's size), into --out as {scenario, recording}");
  app.add_flag("!--no-secure", options.secure, "skip the runs with DDS Security (--secure)");
  app.add_option("--security-rounds", options.security_rounds,
                 "rounds of an unsecured and a secured run, in alternating order (median security_cost)")
      ->check(CLI::Range(1, 20));
  app.add_flag("--security-only", options.security_only,
               "only the security rounds (security_cost and where the CPU went), into --out as {scenario, security}");
  app.add_flag("--hires", options.hires, "only `bench: e2e-hires:`: crack-descent-hires with 1 and 2 sealing shards");
  app.add_option("--hires-duration-s", options.hires_duration_s, "simulated seconds of each hires run");
  app.add_option("--hires-compose", options.hires_compose, "the 2-shard layout of --hires (a compose file)");
  app.add_option("--hires-rounds", options.hires_rounds, "rounds of the three --hires layouts (median ratios)")
      ->check(CLI::Range(1, 20));
  app.add_option("--robot", options.robot,
                 "the shipped robot whose crack scenario (crack-<robot>) runs beside CROMSCI's crack-descent; "
                 "all (default) or none");
  app.add_option("--robot-rounds", options.robot_rounds, "rounds of the robots' crack runs (median ratios)")
      ->check(CLI::Range(1, 20));
  app.add_option("--robot-target", options.robot_target, "a robot's realtime_factor / CROMSCI's, at least");
  app.add_flag("--robots-only", options.robots_only, "only the robots' crack runs beside CROMSCI's (--robot)");
  return climbsim::guardedMain(app, argc, argv, "bench-e2e", [&] {
    // Absolute: the paths are handed to processes that run elsewhere (the attach script).
    if (!options.root.empty()) options.root = fs::absolute(options.root).lexically_normal().string();
    if (!options.build.empty()) options.build = fs::absolute(options.build).lexically_normal().string();
    if (options.recording_only) return runRecordingOnly(options);
    if (options.security_only) return runSecurityOnly(options);
    if (options.hires) return runHires(options);
    return options.robots_only ? runRobotsOnly(options) : run(options);
  });
}
