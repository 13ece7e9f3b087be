/// climbsim-downforce-log: logs the downforce once a second of simulated time, e.g.
/// "t = 3.000 s: F = 2187.4 N (set-point 2200 N)". An observer: never on the clock's roster,
/// never gates a step (compose file entry with `observer: true`).

#include <cmath>
#include <csignal>

#include <atomic>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "downforce_log.hpp"
#include "downforce_reader.hpp"
#include "downforce_translate.hpp"

namespace {
std::atomic<bool> g_quit{false};
}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::downforce_log;
  CLI::App app{"climbsim-downforce-log: logs the downforce once a second of simulated time (an observer)"};
  DdsSettings dds;
  std::string name = "downforce_log";
  double every_s = 1.0;
  dds.addOptions(app);
  app.add_option("--name", name, "DDS participant name (logs)");
  app.add_option("--every-s", every_s, "simulated time between two lines [s]")->check(CLI::Range(0.001, 3600.0));
  return guardedMain(app, argc, argv, "downforce_log", [&]() -> int {
    std::signal(SIGINT, [](int) { g_quit = true; });
    std::signal(SIGTERM, [](int) { g_quit = true; });
    initLogging(name);
    dds.resolve();
    const DownforceLog model(DownforceLogParams{std::llround(every_s * 1e9)});
    auto state = model.initialState();
    DownforceReader reader(dds, name);
    reader.follow(
        [&](const AdhesionForce& sample, std::int64_t dt_ns) {
          const auto out = model.step(state, inputsFromIdl(sample), sample.t_ns(), dt_ns);
          if (out.due) spdlog::info("{}", out.line);
        },
        g_quit);
    return kExitOk;
  });
}
