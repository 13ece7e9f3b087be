#include "downforce_reader.hpp"

#include <chrono>
#include <optional>

#include "climbsim/dds_context.hpp"
#include "climbsim/topic_names.hpp"
#include "clockPubSubTypes.h"
#include "thermoPubSubTypes.h"

namespace climbsim::downforce_log {

struct DownforceReader::Endpoints {
  Endpoints(const DdsSettings& settings, const std::string& name)
      : dds(settings, name),
        run_start(dds, topic::kRunStart, qos::kLatched, notifier),
        sim_time(dds, topic::kSimTime, qos::kObserver, notifier),
        stop(dds, topic::kStop, qos::kLatched, notifier) {}

  Notifier notifier;
  DdsContext dds;
  Reader<RunStartPubSubType> run_start;
  Reader<SimTimePubSubType> sim_time;
  Reader<StopPubSubType> stop;
  std::unique_ptr<Reader<AdhesionForcePubSubType>> force;  ///< once the run is under way
};

DownforceReader::DownforceReader(const DdsSettings& settings, const std::string& name)
    : endpoints_(std::make_unique<Endpoints>(settings, name)) {}

DownforceReader::~DownforceReader() = default;

bool DownforceReader::follow(const OnSample& on_sample, const std::atomic<bool>& quit) {
  auto& e = *endpoints_;
  std::optional<std::uint64_t> run_id;
  std::int64_t dt_ns = 0;
  bool sim_time_seen = false;
  const auto hand_on = [&] {
    if (!e.force) return;
    for (const auto& received : e.force->take()) on_sample(received.data, dt_ns);
  };
  while (!quit) {
    const auto seen = e.notifier.generation();
    for (const auto& received : e.run_start.take()) {
      if (!run_id) {
        run_id = received.data.run_id();
        dt_ns = received.data.dt_ns();
      }
    }
    sim_time_seen = !e.sim_time.take().empty() || sim_time_seen;
    if (run_id && sim_time_seen && !e.force) {
      e.force = std::make_unique<Reader<AdhesionForcePubSubType>>(e.dds, topic::kAdhesionForce, qos::kObserver,
                                                                 e.notifier);
    }
    hand_on();
    for (const auto& received : e.stop.take()) {
      if (run_id && received.data.run_id() == *run_id) {
        hand_on();
        return true;
      }
    }
    // Woken by any reader's news; the timeout only bounds how long a quit waits.
    e.notifier.waitChanged(seen, Notifier::Clock::now() + std::chrono::milliseconds(200));
  }
  return false;
}

}  // namespace climbsim::downforce_log
