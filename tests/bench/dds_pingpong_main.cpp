/// climbsim-bench-pingpong: the raw Fast DDS round trip between two processes, the
/// physical limit of one lockstep step (tests/bench, `./deploy/climbsim bench clock`).
///
/// Separate processes, `--role pong` and `--role ping`, on the same domain. Ping writes a
/// TestSample on "bench/ping", pong echoes it on "bench/pong". Both topics use the
/// `climbsim.control` QoS profile (the lockstep's grant and done) and both sides wake up
/// the way the lockstep does: the reader's listener notifies a Notifier, the waiting
/// thread takes the sample and answers. Ping waits until both directions are matched,
/// warms up, measures N round trips and prints one machine-readable line on stdout:
///
///   pingpong: n=N pongs=K payload=P profile=.. rtt_us_median=.. rtt_us_p99=.. rtt_us_mean=.. rtt_us_min=.. rtt_us_max=..
///
/// With `--pongs K` (K pong processes, distinct `--name`s), a round trip ends when every
/// pong has echoed: the fan-out of one grant to K participants and their K dones.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/dds_context.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/logging.hpp"
#include "testingPubSubTypes.h"

namespace {

using SteadyClock = std::chrono::steady_clock;
using climbsim::Notifier;
using climbsim::Reader;
using climbsim::Writer;
using climbsim::TestSamplePubSubType;

constexpr const char* kPingTopic = "bench/ping";
constexpr const char* kPongTopic = "bench/pong";
/// `step` of the sample that tells pong to leave.
constexpr std::uint64_t kQuitStep = std::numeric_limits<std::uint64_t>::max();

struct Options {
  std::string role;
  std::string name = "pong";               ///< pong: the `source` of its echoes
  std::string profile = climbsim::qos::kControl;
  int pongs = 1;                           ///< ping: echoes that end a round trip
  climbsim::DdsSettings dds;
  int round_trips = 5000;
  int warmup = 500;
  std::size_t payload = 0;       ///< doubles per sample
  double match_timeout_s = 30.0;  ///< discovery and the first round trip
  double rtt_timeout_s = 5.0;     ///< one measured round trip
};

SteadyClock::time_point after(double seconds) {
  return SteadyClock::now() +
         std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
}

/// Waits on the notifier until `ready()` holds; false at the deadline.
template <class Pred>
bool waitFor(Notifier& notifier, SteadyClock::time_point deadline, Pred ready) {
  while (true) {
    const auto seen = notifier.generation();
    if (ready()) {
      return true;
    }
    if (SteadyClock::now() >= deadline) {
      return false;
    }
    notifier.waitChanged(seen, deadline);
  }
}

int runPong(const Options& opt) {
  Notifier notifier;
  climbsim::DdsContext dds(opt.dds, "bench-" + opt.name);
  Reader<TestSamplePubSubType> in(dds, kPingTopic, opt.profile, notifier);
  Writer<TestSamplePubSubType> out(dds, kPongTopic, opt.profile, notifier);
  spdlog::info("pong: waiting for ping on domain {}", opt.dds.domain_id);
  bool seen_ping = false;
  // Pings that arrive before our writer has matched ping's reader wait here: a VOLATILE
  // writer never delivers to a reader it matches later, and ping, seeing only its own
  // reader's side of that match, would wait for an echo that never comes.
  std::vector<climbsim::TestSample> pending;
  bool writer_matched = false;
  const auto first_ping_deadline = after(opt.match_timeout_s);
  while (true) {
    const auto seen = notifier.generation();
    bool got_any = false;
    for (auto& got : in.take()) {
      got_any = true;
      if (got.data.step() == kQuitStep) {
        spdlog::info("pong: ping is done");
        return climbsim::kExitOk;
      }
      got.data.source(opt.name);
      pending.push_back(std::move(got.data));
      seen_ping = true;
    }
    writer_matched = writer_matched || out.matchedReaders() > 0;
    if (!pending.empty() && writer_matched) {
      for (auto& echo : pending) {
        out.write(echo);
      }
      pending.clear();
    }
    // Ping vanished without its quit sample: do not linger. (Not checked on the hot path.)
    if (seen_ping && !got_any && in.matchedWriters() == 0) {
      spdlog::warn("pong: ping left without the quit sample");
      return climbsim::kExitFailed;
    }
    const auto now = SteadyClock::now();
    if (!seen_ping && now >= first_ping_deadline) {
      spdlog::error("pong: no ping within {} s", opt.match_timeout_s);
      return climbsim::kExitFailed;
    }
    // Data and unmatching both notify; the bound only guards the deadline above.
    notifier.waitChanged(seen, now + std::chrono::milliseconds(200));
  }
}

double percentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) {
    return 0.0;
  }
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(pos);
  const auto hi = std::min(lo + 1, sorted.size() - 1);
  const double frac = pos - static_cast<double>(lo);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * frac;
}

int runPing(const Options& opt) {
  Notifier notifier;
  climbsim::DdsContext dds(opt.dds, "bench-ping");
  Writer<TestSamplePubSubType> out(dds, kPingTopic, opt.profile, notifier);
  Reader<TestSamplePubSubType> in(dds, kPongTopic, opt.profile, notifier);

  const auto t_discovery = SteadyClock::now();
  if (!waitFor(notifier, after(opt.match_timeout_s),
               [&] { return out.matchedReaders() >= opt.pongs && in.matchedWriters() >= opt.pongs; })) {
    spdlog::error("ping: pong not matched within {} s (readers {}, writers {})", opt.match_timeout_s,
                  out.matchedReaders(), in.matchedWriters());
    return climbsim::kExitFailed;
  }
  spdlog::info("ping: matched after {:.3f} s",
               std::chrono::duration<double>(SteadyClock::now() - t_discovery).count());

  climbsim::TestSample sample;
  sample.source("ping");
  sample.payload().assign(opt.payload, 0.0);
  std::uint64_t seq = 0;

  // One round trip: write seq, wait until every pong's echo of seq arrives. Our writer has
  // matched every pong's reader (the side that counts for a VOLATILE writer); each pong
  // holds its echo until its writer has matched our reader.
  auto roundTrip = [&](double timeout_s) -> std::optional<double> {
    ++seq;
    sample.step(seq);
    sample.t_ns(static_cast<std::int64_t>(seq));
    const auto t0 = SteadyClock::now();
    out.write(sample);
    std::set<std::string> back;
    const bool ok = waitFor(notifier, after(timeout_s), [&] {
      for (auto& got : in.take()) {
        if (got.data.step() == seq) {
          back.insert(got.data.source().c_str());
        }
      }
      return static_cast<int>(back.size()) >= opt.pongs;
    });
    if (!ok) {
      return std::nullopt;
    }
    return std::chrono::duration<double, std::micro>(SteadyClock::now() - t0).count();
  };

  for (int i = 0; i < opt.warmup; ++i) {
    if (!roundTrip(i == 0 ? opt.match_timeout_s : opt.rtt_timeout_s)) {
      spdlog::error("ping: warm-up round trip {} got no answer", i);
      return climbsim::kExitFailed;
    }
  }
  std::vector<double> rtt_us;
  rtt_us.reserve(static_cast<std::size_t>(opt.round_trips));
  for (int i = 0; i < opt.round_trips; ++i) {
    const auto rtt = roundTrip(opt.rtt_timeout_s);
    if (!rtt) {
      spdlog::error("ping: round trip {} got no answer within {} s", i, opt.rtt_timeout_s);
      return climbsim::kExitFailed;
    }
    rtt_us.push_back(*rtt);
  }

  sample.step(kQuitStep);
  out.write(sample);

  std::sort(rtt_us.begin(), rtt_us.end());
  const double mean = std::accumulate(rtt_us.begin(), rtt_us.end(), 0.0) / static_cast<double>(rtt_us.size());
  std::printf("pingpong: n=%zu pongs=%d payload=%zu profile=%s rtt_us_median=%.1f rtt_us_p99=%.1f rtt_us_mean=%.1f rtt_us_min=%.1f "
              "rtt_us_max=%.1f\n",
              rtt_us.size(), opt.pongs, opt.payload, opt.profile.c_str(), percentile(rtt_us, 0.5), percentile(rtt_us, 0.99), mean, rtt_us.front(),
              rtt_us.back());
  std::fflush(stdout);

  // Let pong read the quit sample before our writer disappears.
  waitFor(notifier, after(2.0), [&] { return in.matchedWriters() == 0; });
  return climbsim::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-pingpong: Fast DDS round trip between two processes (climbsim.control QoS)"};
  Options opt;
  app.add_option("--role", opt.role, "ping (measures) or pong (echoes)")
      ->required()
      ->check(CLI::IsMember({"ping", "pong"}));
  app.add_option("--name", opt.name, "pong: name written as the source of its echoes (unique per pong)");
  app.add_option("--pongs", opt.pongs, "ping: number of pong processes that answer each ping")
      ->check(CLI::PositiveNumber);
  app.add_option("--profile", opt.profile, "QoS profile of both topics (default climbsim.control)");
  app.add_option("--round-trips", opt.round_trips, "measured round trips (ping)")->check(CLI::PositiveNumber);
  app.add_option("--warmup", opt.warmup, "round trips before measuring (ping, >= 1)")->check(CLI::PositiveNumber);
  app.add_option("--payload", opt.payload, "doubles of payload per sample");
  app.add_option("--match-timeout-s", opt.match_timeout_s, "limit for discovery and the first round trip [s]");
  app.add_option("--rtt-timeout-s", opt.rtt_timeout_s, "limit for one round trip [s]");
  opt.dds.addOptions(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? climbsim::kExitOk : climbsim::kExitConfig;
  }
  climbsim::initLogging(opt.role == "pong" ? "bench-" + opt.name : "bench-ping");
  try {
    opt.dds.resolve();
    return opt.role == "ping" ? runPing(opt) : runPong(opt);
  } catch (const climbsim::ConfigError& e) {
    spdlog::error("{}", e.what());
    return climbsim::kExitConfig;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return climbsim::kExitFailed;
  }
}
