/// climbsim-sweep SCENARIO --set KEY=V1,V2,... [--set KEY2=...] [-j N | --ray ADDRESS] [--distributed]
/// --out DIR: runs the scenario once per combination of the values (the cartesian product),
/// each variant in its own process: climbsim-solo (default) or `climbsim-compose run` on a DDS
/// domain of its own (--distributed); N at a time on this machine, or each variant a task of a
/// Ray cluster (--ray, sweep/ray_pool.hpp). Writes DIR/<variant>/ (a run directory each, and
/// DIR/<variant>.log), DIR/sweep.csv (a row per finished variant) and the overlay plots
/// DIR/downforce.png and DIR/pf.png. A progress line on stderr. Every key and value is checked
/// before any variant starts (one line, exit 2). Ctrl-C (SIGINT, SIGTERM) stops the variants
/// under way, keeps the finished ones in sweep.csv and the plots, exit 4. Exit 0 when every
/// variant finished (completed or fell), 1 when one failed or the cluster could not run them.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/scenario.hpp"
#include "sweep/local_pool.hpp"
#include "sweep/ray_pool.hpp"
#include "sweep/sweep_progress.hpp"
#include "sweep/sweep_results.hpp"
#include "sweep/sweep_spec.hpp"

#ifndef CLIMBSIM_ROOT
#error "CLIMBSIM_ROOT must name the repository (deploy/scenarios)"
#endif
#ifndef CLIMBSIM_BUILD_DIR
#error "CLIMBSIM_BUILD_DIR must name the build directory (programs in bin/)"
#endif

namespace {
namespace fs = std::filesystem;
std::atomic<bool> g_stop{false};
extern "C" void onSignal(int) { g_stop.store(true); }

/// The command of a variant: climbsim-solo, or the default composition on a DDS domain of its own.
std::vector<std::string> commandOf(const climbsim::sweep::Variant& v, const std::string& scenario_file,
                                   const std::string& dir, bool distributed, bool no_mcap) {
  const std::string bin = std::string(CLIMBSIM_BUILD_DIR) + "/bin/";
  std::vector<std::string> argv =
      distributed ? std::vector<std::string>{bin + "climbsim-compose", "--root", CLIMBSIM_ROOT, "--build",
                                             CLIMBSIM_BUILD_DIR, "run", scenario_file, "--out", dir, "--name",
                                             "sweep-" + std::to_string(::getpid()) + "-" + std::to_string(v.index)}
                  : std::vector<std::string>{bin + "climbsim-solo", scenario_file, "--out", dir, "--no-plots"};
  if (no_mcap) argv.push_back("--no-mcap");
  for (const auto& o : v.overrides) argv.insert(argv.end(), {"--set", o});
  return argv;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::sweep;
  CLI::App app{"climbsim-sweep: one scenario over the cartesian product of values of its keys"};
  std::string scenario, out_dir, ray;
  std::vector<std::string> sets;
  unsigned jobs = 0;
  double cpus_per_variant = 0;
  bool distributed = false;
  bool no_mcap = false;
  app.add_option("SCENARIO", scenario, "scenario file or name in deploy/scenarios")->required();
  app.add_option("--set", sets, "KEY=V1,V2,...: the values of a scenario key to sweep (repeatable; one value: fixed)")
      ->required();
  app.add_option("--out", out_dir, "sweep directory: a run directory per variant, sweep.csv, overlay plots")
      ->required();
  auto* jobs_option =
      app.add_option("-j,--jobs", jobs, "variants at a time on this machine (default: solo the number of cores, "
                                        "--distributed 1)");
  app.add_option("--ray", ray, "run each variant as a task of the Ray cluster at ADDRESS (HOST:PORT, or auto: the "
                               "one `climbsim cluster up` started); every node needs this checkout and build at "
                               "the same path")
      ->excludes(jobs_option);
  app.add_option("--cpus-per-variant", cpus_per_variant,
                 "CPUs a variant's Ray task reserves (default: solo 1, --distributed 2)");
  app.add_flag("--distributed", distributed,
               "run each variant as the default composition (`climbsim run`, every service a process, a DDS "
               "domain of its own) instead of climbsim-solo");
  app.add_flag("--no-mcap", no_mcap,
               "no run.mcap in a variant's directory (trace.csv, summary.json and the plots only): less disk, "
               "and each variant renders no whole depth frames for the recording's depth grids")
      ->excludes("--distributed");
  return guardedMain(app, argc, argv, "sweep", [&]() -> int {
    const std::string scenario_file =
        scenario.find('/') != std::string::npos || fs::path(scenario).extension() == ".yaml"
            ? fs::absolute(scenario).string()
            : std::string(CLIMBSIM_ROOT) + "/deploy/scenarios/" + scenario + ".yaml";
    if (!fs::exists(scenario_file)) throw ConfigError("SCENARIO = " + scenario + ": no such file (" + scenario_file + ")");
    std::vector<SweepAxis> axes;
    for (const auto& set : sets) axes.push_back(parseAxis(set));
    const std::vector<Variant> variants = variantsOf(axes);
    // Every variant's scenario loads before any starts: an unknown key or a bad value is one line.
    std::vector<double> hold_s;  // by variant index
    std::vector<VariantJob> work;
    for (const auto& v : variants) {
      const Scenario s = loadScenario(scenario_file, v.overrides);
      hold_s.push_back(s.start.hold_s);
      if (!distributed && s.controller.kind == Scenario::ControllerKind::kExternal) {
        throw ConfigError(scenario_file + ": controller.type = external: a solo run cannot host an external "
                          "controller (use --distributed with a compose file that starts one)");
      }
      const std::string dir = (fs::path(out_dir) / v.name).string();
      work.push_back({v, commandOf(v, scenario_file, fs::absolute(dir).string(), distributed, no_mcap), dir});
    }
    if (jobs == 0) jobs = distributed ? 1u : std::max(1u, std::thread::hardware_concurrency());
    if (cpus_per_variant <= 0) cpus_per_variant = distributed ? 2.0 : 1.0;
    fs::create_directories(out_dir);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const bool live = ::isatty(STDERR_FILENO) != 0;
    std::unique_ptr<VariantPool> pool;
    if (ray.empty()) {
      spdlog::info("sweep: {} variants of {}, {} at a time, {}; into {}", variants.size(), scenario_file, jobs,
                   distributed ? "distributed" : "solo", out_dir);
      pool = std::make_unique<LocalPool>(work, jobs);
    } else {
      spdlog::info("sweep: {} variants of {} on the Ray cluster {}, {} CPUs each, {}; into {}", variants.size(),
                   scenario_file, ray, cpus_per_variant, distributed ? "distributed" : "solo", out_dir);
      pool = std::make_unique<RayPool>(
          work, RayOptions{std::string(CLIMBSIM_BUILD_DIR) + "/bin/climbsim-ray-sweep", ray, cpus_per_variant,
                           out_dir, CLIMBSIM_ROOT, {scenario_file}, std::string(CLIMBSIM_BUILD_DIR) + "/ray/address"});
    }

    std::vector<VariantResult> results;
    SweepCounts counts;
    counts.total = variants.size();
    const auto started = std::chrono::steady_clock::now();
    std::string last_line;
    auto progress = [&](bool force_line) {
      const auto load = pool->load();
      counts.running = load.running;
      counts.queued = load.queued;
      const std::string line =
          progressLine(counts, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
      if (live) {
        std::fprintf(stderr, "\r%s\033[K", line.c_str());
      } else if (force_line && line != last_line) {
        std::fprintf(stderr, "%s\n", line.c_str());
      }
      last_line = line;
    };
    bool stopping = false;
    while (!pool->finished()) {
      if ((g_stop.load() || pool->fatal()) && !stopping) {
        stopping = true;
        pool->stop();
      }
      for (const auto& end : pool->poll()) {
        const Variant& v = variants.at(end.index);
        const std::string dir = (fs::path(out_dir) / v.name).string();
        if (end.stopped) continue;  // not finished: left out of sweep.csv (its directory keeps what it computed)
        ++counts.done;
        if (!end.exit_code) {
          ++counts.failed;
          spdlog::warn("sweep: variant {} did not run to its end: {}", v.name, end.note);
          continue;
        }
        const int code = *end.exit_code;
        try {
          results.push_back(readVariant(v, dir, end.wall_s, hold_s.at(v.index)));
          VariantResult& r = results.back();
          if (code != kExitOk && code != kExitFell) r.outcome = "failed";
          counts.fell += r.fell ? 1 : 0;
          counts.slid += r.slid && !r.fell ? 1 : 0;
          counts.failed += r.outcome == "failed" ? 1 : 0;
          if (r.fell || r.outcome == "failed") {
            if (live) std::fprintf(stderr, "\r\033[K");  // the line goes above the progress line
            spdlog::warn("sweep: variant {} {}: {}", v.name, r.fell ? "fell" : "failed", r.reason);
          }
        } catch (const std::exception& e) {
          ++counts.failed;
          spdlog::warn("sweep: variant {} (exit {}): {}; see {}.log", v.name, code, e.what(), dir);
        }
        progress(true);
      }
      progress(false);
      if (!pool->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(50));  // polling children
    }
    if (live) std::fprintf(stderr, "\n");
    std::sort(results.begin(), results.end(),
              [](const VariantResult& a, const VariantResult& b) { return a.variant.index < b.variant.index; });
    std::ofstream(fs::path(out_dir) / "sweep.csv") << sweepCsv(axes, results);
    if (!results.empty()) {
      cv::imwrite((fs::path(out_dir) / "downforce.png").string(), downforceOverlay(axes, results));
      cv::imwrite((fs::path(out_dir) / "pf.png").string(), pfOverlay(axes, results));
    }
    spdlog::info("sweep: {} of {} variants finished ({} fell, {} slid beyond their slide limit, {} failed); {}/sweep.csv",
                 counts.done, variants.size(), counts.fell, counts.slid, counts.failed, out_dir);
    if (const auto fatal = pool->fatal()) {
      spdlog::error("sweep: {}", *fatal);
      return kExitFailed;
    }
    if (g_stop.load()) {
      spdlog::warn("sweep: stopped; the {} finished variants are kept", counts.done);
      return kExitStopped;
    }
    return counts.failed > 0 ? kExitFailed : kExitOk;
  });
}
