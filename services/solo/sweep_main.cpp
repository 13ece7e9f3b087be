/// climbsim-sweep SCENARIO --set KEY=V1,V2,... [--set KEY2=...] [-j N] [--distributed] --out DIR:
/// runs the scenario once per combination of the values (the cartesian product), N at a time,
/// each variant in its own process: climbsim-solo (default) or `climbsim-compose run` on a DDS
/// domain of its own (--distributed). Writes DIR/<variant>/ (a run directory each, and
/// DIR/<variant>.log), DIR/sweep.csv (a row per finished variant) and the overlay plots
/// DIR/downforce.png and DIR/pf.png. A progress bar on stderr. Every key and value is checked
/// before any variant starts (one line, exit 2). Ctrl-C (SIGINT, SIGTERM) stops the variants
/// under way, keeps the finished ones in sweep.csv and the plots, exit 4. Exit 0 when every
/// variant finished (completed or fell), 1 when one failed.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/process.hpp"
#include "climbsim/scenario.hpp"
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

/// A variant's process under way.
struct Running {
  climbsim::sweep::Variant variant;
  std::unique_ptr<climbsim::ChildProcess> process;
  std::chrono::steady_clock::time_point started;
  bool signalled = false;
};

/// "[#####.....] 3/8 done (1 fell, 0 failed), 2 running, 12 s"
std::string progressLine(std::size_t done, std::size_t total, std::size_t fell, std::size_t failed,
                         std::size_t running, double elapsed_s) {
  constexpr int kWidth = 30;
  const int filled = total > 0 ? static_cast<int>(kWidth * done / total) : kWidth;
  char text[200];
  std::snprintf(text, sizeof(text), "sweep: [%s%s] %zu/%zu done (%zu fell, %zu failed), %zu running, %.0f s",
                std::string(static_cast<std::size_t>(filled), '#').c_str(),
                std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), done, total, fell, failed,
                running, elapsed_s);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::sweep;
  CLI::App app{"climbsim-sweep: one scenario over the cartesian product of values of its keys"};
  std::string scenario;
  std::vector<std::string> sets;
  std::string out_dir;
  unsigned jobs = 0;
  bool distributed = false;
  app.add_option("SCENARIO", scenario, "scenario file or name in deploy/scenarios")->required();
  app.add_option("--set", sets, "KEY=V1,V2,...: the values of a scenario key to sweep (repeatable; one value: fixed)")
      ->required();
  app.add_option("--out", out_dir, "sweep directory: a run directory per variant, sweep.csv, overlay plots")
      ->required();
  app.add_option("-j,--jobs", jobs, "variants at a time (default: solo the number of cores, --distributed 1)");
  app.add_flag("--distributed", distributed,
               "run each variant as the default composition (`climbsim run`, every service a process, a DDS "
               "domain of its own) instead of climbsim-solo");
  return guardedMain(app, argc, argv, "sweep", [&]() -> int {
    const std::string scenario_file =
        scenario.find('/') != std::string::npos || fs::path(scenario).extension() == ".yaml"
            ? scenario
            : std::string(CLIMBSIM_ROOT) + "/deploy/scenarios/" + scenario + ".yaml";
    if (!fs::exists(scenario_file)) throw ConfigError("SCENARIO = " + scenario + ": no such file (" + scenario_file + ")");
    std::vector<SweepAxis> axes;
    for (const auto& set : sets) axes.push_back(parseAxis(set));
    const std::vector<Variant> variants = variantsOf(axes);
    // Every variant's scenario loads before any starts: an unknown key or a bad value is one line.
    std::vector<double> hold_s;  // by variant index
    for (const auto& v : variants) {
      const Scenario s = loadScenario(scenario_file, v.overrides);
      hold_s.push_back(s.start.hold_s);
      if (!distributed && s.controller.kind == Scenario::ControllerKind::kExternal) {
        throw ConfigError(scenario_file + ": controller.type = external: a solo run cannot host an external "
                          "controller (use --distributed with a compose file that starts one)");
      }
    }
    if (jobs == 0) jobs = distributed ? 1u : std::max(1u, std::thread::hardware_concurrency());
    fs::create_directories(out_dir);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const bool live = ::isatty(STDERR_FILENO) != 0;
    spdlog::info("sweep: {} variants of {}, {} at a time, {}; into {}", variants.size(), scenario_file, jobs,
                 distributed ? "distributed" : "solo", out_dir);

    std::deque<Variant> waiting(variants.begin(), variants.end());
    std::vector<Running> running;
    std::vector<VariantResult> results;
    std::size_t fell = 0, failed = 0, finished = 0;
    const auto started = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
    std::string last_line;
    auto progress = [&](bool force_line) {
      const std::string line = progressLine(finished, variants.size(), fell, failed, running.size(), elapsed());
      if (live) {
        std::fprintf(stderr, "\r%s\033[K", line.c_str());
      } else if (force_line && line != last_line) {
        std::fprintf(stderr, "%s\n", line.c_str());
      }
      last_line = line;
    };
    while (!waiting.empty() || !running.empty()) {
      while (!g_stop.load() && !waiting.empty() && running.size() < jobs) {
        Variant v = waiting.front();
        waiting.pop_front();
        const std::string dir = (fs::path(out_dir) / v.name).string();
        fs::remove_all(dir);
        ProcessSpec spec;
        if (distributed) {
          spec.argv = {std::string(CLIMBSIM_BUILD_DIR) + "/bin/climbsim-compose", "--root", CLIMBSIM_ROOT, "--build",
                       CLIMBSIM_BUILD_DIR, "run", scenario_file, "--out", dir,
                       "--name", "sweep-" + std::to_string(::getpid()) + "-" + std::to_string(v.index)};
        } else {
          spec.argv = {std::string(CLIMBSIM_BUILD_DIR) + "/bin/climbsim-solo", scenario_file, "--out", dir,
                       "--no-plots"};
        }
        for (const auto& o : v.overrides) spec.argv.insert(spec.argv.end(), {"--set", o});
        spec.output_file = dir + ".log";
        fs::remove(spec.output_file);
        running.push_back({v, std::make_unique<ChildProcess>(spec), std::chrono::steady_clock::now(), false});
      }
      if (g_stop.load()) {
        waiting.clear();
        for (auto& r : running) {
          if (!r.signalled) r.process->signal(SIGINT);  // each stops after its step under way
          r.signalled = true;
        }
      }
      for (auto it = running.begin(); it != running.end();) {
        const auto code = it->process->poll();
        if (!code) {
          ++it;
          continue;
        }
        const double wall_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - it->started).count();
        const std::string dir = (fs::path(out_dir) / it->variant.name).string();
        if (*code == kExitStopped || (it->signalled && *code != kExitOk && *code != kExitFell)) {
          // Not finished: left out of sweep.csv (its directory keeps what it computed).
        } else {
          ++finished;
          try {
            results.push_back(readVariant(it->variant, dir, wall_s, hold_s.at(it->variant.index)));
            if (results.back().fell) ++fell;
            if (*code != kExitOk && *code != kExitFell) {
              ++failed;
              results.back().outcome = "failed";
            }
          } catch (const std::exception& e) {
            ++failed;
            spdlog::warn("sweep: variant {} (exit {}): {}; see {}.log", it->variant.name, *code, e.what(), dir);
          }
        }
        it = running.erase(it);
        progress(true);
      }
      progress(false);
      if (!running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));  // polling children
    }
    if (live) std::fprintf(stderr, "\n");
    std::sort(results.begin(), results.end(),
              [](const VariantResult& a, const VariantResult& b) { return a.variant.index < b.variant.index; });
    std::ofstream(fs::path(out_dir) / "sweep.csv") << sweepCsv(axes, results);
    if (!results.empty()) {
      cv::imwrite((fs::path(out_dir) / "downforce.png").string(), downforceOverlay(axes, results));
      cv::imwrite((fs::path(out_dir) / "pf.png").string(), pfOverlay(axes, results));
    }
    spdlog::info("sweep: {} of {} variants finished ({} fell, {} failed); {}/sweep.csv", finished, variants.size(),
                 fell, failed, out_dir);
    if (g_stop.load()) {
      spdlog::warn("sweep: stopped; the {} finished variants are kept", finished);
      return kExitStopped;
    }
    return failed > 0 ? kExitFailed : kExitOk;
  });
}
