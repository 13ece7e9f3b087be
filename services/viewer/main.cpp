/// climbsim-viewer: the live 3D view and dashboard in the browser (an observer: never on the
/// roster, never gates a step), and the replay of a finished run directory (--replay).

#include <sys/resource.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/scenario.hpp"
#include "client_command.hpp"
#include "frame_pacer.hpp"
#include "climbsim/grid_record.hpp"
#include "climbsim/height_grid.hpp"
#include "live_state.hpp"
#include "replay_run.hpp"
#include "run_description.hpp"
#include "viewer_node.hpp"
#include "web_server.hpp"

namespace {
namespace fs = std::filesystem;
using namespace climbsim;
using namespace climbsim::viewer;
using SteadyClock = std::chrono::steady_clock;

std::atomic<bool> g_quit{false};

std::int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(SteadyClock::now().time_since_epoch()).count();
}

std::string readBinary(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

HttpResponse json(const nlohmann::json& value) { return {200, "application/json", value.dump()}; }

struct Options {
  std::string scenario_file;
  std::string replay_dir;
  std::string name = "viewer";
  WebServer::Options web;
  double max_fps = 30.0;             ///< states looked at per second (samples plotted)
  double messages_per_s = 10.0;      ///< messages per second to each page, each with its samples
  double depth_fps = 1.0;            ///< depth grids per second (the wall under the robot)
  int depth_cells = 128;
  double linger_s = 2.0;
  bool no_depth = false;             ///< no wall relief (no depth grids, no depth images)
  int nice = 10;                     ///< CPU priority of the live viewer (0 = as the run's services)
};

/// Serves a finished run: the page fetches the trace and pictures and replays them itself.
int replay(const Options& options) {
  const fs::path dir = fs::absolute(options.replay_dir);
  if (!fs::is_directory(dir)) throw ConfigError(options.replay_dir + ": no such run directory");
  const std::string trace_file = (dir / "trace.csv").string();
  if (!fs::exists(trace_file)) throw ConfigError(trace_file + ": no trace.csv: not a run directory");
  const std::string scenario_file = (dir / "scenario.yaml").string();
  if (!fs::exists(scenario_file)) throw ConfigError(scenario_file + ": missing: not a run directory");
  const std::string hello = helloJson("replay", loadScenario(scenario_file)).dump();
  const nlohmann::json trace_columns = loadTraceColumns(trace_file);
  const std::string trace = trace_columns.dump();
  const nlohmann::json pictures = listSealingPictures(dir.string());
  const auto grids = loadGridRecords(gridRecordPath(dir.string()));
  WebServer server(options.web);
  server.handle("/api/", [&](const std::string& path, const std::string& query) -> HttpResponse {
    if (path == "/api/hello") return {200, "application/json", hello};
    if (path == "/api/trace") return {200, "application/json", trace};
    if (path == "/api/pictures") return json(pictures);
    if (path == "/api/depth") {  // ?t=<seconds>: the wall under the robot then, if recorded
      const auto at = query.find("t=");
      const double t_s = at == std::string::npos ? 0.0 : std::strtod(query.c_str() + at + 2, nullptr);
      const std::string& grid = gridAt(grids, t_s);
      return grid.empty() ? HttpResponse{200, "application/json", "null"} : HttpResponse{200, "application/json", grid};
    }
    return {404, "text/plain", "no such data: " + path + "\n"};
  });
  server.handle("/run/", [&](const std::string& path, const std::string&) -> HttpResponse {
    for (const auto& picture : pictures) {  // only what the listing offers: no path escapes
      if (path == "/run/" + picture["file"].get<std::string>()) {
        return {200, "image/png", readBinary(dir / picture["file"].get<std::string>())};
      }
    }
    return {404, "text/plain", "not found: " + path + "\n"};
  });
  spdlog::info("replay of {} ({} rows, {} depth grids, {} sealing pictures) at {}", dir.string(),
               trace_columns["values"].empty() ? 0 : trace_columns["values"][0].size(), grids.size(), pictures.size(),
               server.url());
  while (!g_quit) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  return kExitOk;
}

/// Observes the run on the DDS domain and pushes it to the pages.
int live(const Options& options, const DdsSettings& dds) {
  // An observer yields the CPU to the run: on a machine whose cores the run's services keep
  // busy, its readers, JSON and sockets wait for idle moments instead of delaying a step.
  // Set before the DDS participant exists, so that its threads inherit it.
  if (options.nice != 0 && setpriority(PRIO_PROCESS, 0, options.nice) != 0) {
    spdlog::warn("--nice {}: setpriority failed ({}); the viewer runs at the run's priority", options.nice,
                 std::strerror(errno));
  }
  std::string hello;
  if (!options.scenario_file.empty()) hello = helloJson("live", loadScenario(options.scenario_file)).dump();
  ViewerNode node(dds, options.name, options.depth_cells, !options.no_depth);
  WebServer server(options.web);
  std::mutex png_mutex;
  std::map<std::string, std::string> sealing_png;
  server.handle("/api/", [&](const std::string& path, const std::string&) -> HttpResponse {
    if (path == "/api/hello") return {200, "application/json", hello.empty() ? R"({"type":"hello","mode":"live"})" : hello};
    return {404, "text/plain", "no such data: " + path + "\n"};
  });
  server.handle("/live/", [&](const std::string& path, const std::string&) -> HttpResponse {
    std::lock_guard<std::mutex> lock(png_mutex);
    for (const auto& [kind, png] : sealing_png) {
      if (path == "/live/sealing_" + kind + ".png") return {200, "image/png", png};
    }
    return {404, "text/plain", "no picture yet: " + path + "\n"};
  });
  server.onClientMessage([&](const std::string& text) {
    const auto parsed = parseClientMessage(text);
    if (const auto* error = std::get_if<std::string>(&parsed)) {
      spdlog::warn("{}", *error);
      return false;
    }
    if (!node.send(std::get<ClockRequest>(parsed))) spdlog::warn("no clock to send the command to");
    return true;
  });
  if (!hello.empty()) server.publish("0hello", hello);
  spdlog::info("open {} (DDS domain {}{})", server.url(), dds.domain_id,
               server.port() != options.web.port ? "; port " + std::to_string(options.web.port) + " is taken" : "");

  LiveState state;
  RateMeter rate;
  FramePacer depth_frames(options.depth_fps);
  FramePacer messages(options.messages_per_s);
  // Twice what one message period holds: the history never grows while no page takes it.
  SampleHistory history(static_cast<std::size_t>(2.0 * options.max_fps / options.messages_per_s) + 2);
  bool frame_pending = false;
  std::optional<nlohmann::json> depth_pending;
  std::optional<std::int64_t> quit_at_ns;
  std::int64_t last_sim_ns = -1;
  // The loop wakes at the frame rate, not per sample: the readers keep only the latest sample
  // (KEEP_LAST 1), so waking for each of the thousands of samples a second would cost wake-ups
  // and copies that nobody sees.
  const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / options.max_fps));
  auto next_tick = SteadyClock::now();
  while (!g_quit) {
    PollResult polled = node.poll(state);
    const std::int64_t now = nowNs();
    if (state.run.t_ns != last_sim_ns) {
      rate.add(now, state.run.t_ns);
      last_sim_ns = state.run.t_ns;
    }
    state.run.rtf_measured = rate.rate();
    if (polled.changed) {
      history.add(state);
      frame_pending = true;
    }
    if (polled.depth) {
      depth_pending = heightGridJson(*polled.depth, polled.depth_step, polled.depth_t_ns);
    }
    if (!polled.sealing_png.empty()) {
      std::lock_guard<std::mutex> lock(png_mutex);
      for (auto& [kind, png] : polled.sealing_png) sealing_png[kind] = std::move(png);
    }
    if (depth_pending && depth_frames.take(now)) {
      server.publish("2depth", depth_pending->dump());
      depth_pending.reset();
    }
    if (frame_pending && messages.take(now)) {  // the latest state and the samples since the last message
      auto frame = frameJson(state);
      frame["samples"] = history.take();
      // Wall time of sending: the page shows how far behind it is (diagnostics, benchmarks).
      frame["wall_unix_ms"] = std::chrono::duration_cast<std::chrono::milliseconds>(
                                  std::chrono::system_clock::now().time_since_epoch())
                                  .count();
      server.publish("1frame", frame.dump());
      frame_pending = false;
    }
    const bool ended = state.run.phase == RunPhase::kCompleted || state.run.phase == RunPhase::kStopped ||
                       state.run.phase == RunPhase::kFailed;
    if (ended && !quit_at_ns) {
      spdlog::info("the run {} ({}); leaving in {} s", phaseName(state.run.phase), state.run.reason,
                   options.linger_s);
      quit_at_ns = now + static_cast<std::int64_t>(options.linger_s * 1e9);
    }
    if (quit_at_ns && now >= *quit_at_ns && !frame_pending) break;
    next_tick = std::max(next_tick + period, SteadyClock::now());
    std::this_thread::sleep_until(next_tick);
  }
  statsAdd("deliveries", static_cast<double>(node.deliveries()));
  writeStatsIfAsked(options.name);  // CLIMBSIM_STATS_DIR (the e2e benchmark)
  return kExitOk;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-viewer: live 3D view and dashboard of a run in the browser, or the replay of a run directory"};
  Options options;
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
    if (!options.replay_dir.empty()) return replay(options);
    dds.resolve();
    return live(options, dds);
  });
}
