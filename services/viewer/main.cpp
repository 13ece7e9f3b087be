/// climbsim-viewer: the live 3D view and dashboard in the browser (an observer: never on the
/// roster, never gates a step: node/live_view.hpp), and the replay of a finished run directory
/// (--replay: node/replay_server.hpp).

#include <csignal>

#include <atomic>

#include <CLI/CLI.hpp>

#include "climbsim/dds_settings.hpp"
#include "climbsim/main_guard.hpp"
#include "configure.hpp"
#include "node/live_view.hpp"
#include "node/replay_server.hpp"

namespace {
std::atomic<bool> g_quit{false};
}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-viewer: live 3D view and dashboard of a run in the browser, or the replay of a run directory"};
  viewer::ViewerOptions options;
  DdsSettings dds;
  std::uint32_t period = 1;
  std::uint32_t offset = 0;
  options.web.web_dir = CLIMBSIM_VIEWER_WEB_DIR;
  dds.addOptions(app);
  app.add_option("--scenario", options.scenario_file, "the run's scenario (robot shape, set-point) for the live view");
  app.add_option("--replay", options.replay_dir, "serve this finished run directory instead of a live run");
  app.add_option("--name", options.name, "DDS participant name (logs)");
  app.add_option("--port", options.web.port, "TCP port of the page")->check(CLI::Range(1, 65535));
  app.add_option("--port-tries", options.web.port_tries,
                 "while --port is taken (another run's viewer), try the next port, up to this many ports in all "
                 "(default 1: a taken --port is an error; `up` gives 20 for the compose file's default port)")
      ->check(CLI::Range(1, 100));
  app.add_option("--bind", options.web.bind, "IPv4 address to listen on (0.0.0.0: every interface of this machine)");
  app.add_option("--web-dir", options.web.web_dir, "the bundled page");
  app.add_option("--fps", options.max_fps, "most states per second looked at and plotted")->check(CLI::Range(1.0, 120.0));
  app.add_option("--messages-per-s", options.messages_per_s, "most WebSocket messages per second to each page")
      ->check(CLI::Range(1.0, 120.0));
  app.add_option("--depth-fps", options.depth_fps, "most depth grids (wall relief) per second to each page")
      ->check(CLI::Range(0.1, 30.0));
  app.add_option("--nice", options.nice, "CPU niceness of the live viewer (0: the run's; 19: the lowest)")
      ->check(CLI::Range(0, 19));
  app.add_flag("--no-depth", options.no_depth, "no wall relief: neither depth grids nor depth images (256 KiB each)");
  app.add_option("--linger-s", options.linger_s, "after the run ended, keep serving this long [s]")
      ->check(CLI::NonNegativeNumber);
  // The launcher appends these to every service; an observer has no schedule.
  app.add_option("--period", period, "ignored (observers have no schedule)");
  app.add_option("--offset", offset, "ignored (observers have no schedule)");
  return guardedMain(app, argc, argv, "viewer", [&]() -> int {
    std::signal(SIGINT, [](int) { g_quit = true; });
    std::signal(SIGTERM, [](int) { g_quit = true; });
    std::signal(SIGPIPE, SIG_IGN);
    if (!options.replay_dir.empty()) return viewer::serveReplay(options, g_quit);
    dds.resolve();
    return viewer::serveLive(options, dds, g_quit);
  });
}
