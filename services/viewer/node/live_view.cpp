#include "live_view.hpp"

#include <sys/resource.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>

#include "climbsim/errors.hpp"
#include "climbsim/height_grid.hpp"
#include "climbsim/run_stats.hpp"
#include "client_command.hpp"
#include "frame_pacer.hpp"
#include "live_state.hpp"
#include "viewer_node.hpp"

namespace climbsim::viewer {
namespace {
using SteadyClock = std::chrono::steady_clock;

std::int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(SteadyClock::now().time_since_epoch()).count();
}
}  // namespace

int serveLive(const ViewerOptions& options, const DdsSettings& dds, const std::atomic<bool>& quit) {
  // An observer yields the CPU to the run: on a machine whose cores the run's services keep
  // busy, its readers, JSON and sockets wait for idle moments instead of delaying a step.
  // Set before the DDS participant exists, so that its threads inherit it.
  if (options.nice != 0 && setpriority(PRIO_PROCESS, 0, options.nice) != 0) {
    spdlog::warn("--nice {}: setpriority failed ({}); the viewer runs at the run's priority", options.nice,
                 std::strerror(errno));
  }
  const std::string hello = helloText("live", options.scenario_file);
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
  while (!quit) {
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

}  // namespace climbsim::viewer
