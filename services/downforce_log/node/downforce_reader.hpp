#pragma once
/// @file
/// The downforce log's DDS side: an observer of one run (never on the clock's roster, never
/// gates a step). It follows the run through the clock's RunStart, SimTime and Stop and hands
/// on every thermo/AdhesionForce sample it receives.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "climbsim/dds_settings.hpp"
#include "thermo.h"

namespace climbsim::downforce_log {

/// Reads one run's downforce on the DDS domain of `settings`.
///
/// The AdhesionForce reader is created only once the run is under way (RunStart and a first
/// SimTime: the clock grants the first horizon only when every roster member has armed). A
/// producer arms when its writers have matched the readers of the participants the roster
/// names as its consumers (by identity), so an observer's reader does not take one's
/// place; created after the start, it also adds no matching to it. The samples of the steps
/// before it matched are not seen. The reader is best effort and
/// keeps the latest sample (QoS profile climbsim.observer): a slow log misses samples, thermo
/// never waits for it. thermo writes AdhesionForce at every step a roster member reads it (the
/// controller and drive do at every step in the shipped compositions).
class DownforceReader {
 public:
  /// Called with each sample and the run's step length dt [ns], in arrival order.
  using OnSample = std::function<void(const AdhesionForce& sample, std::int64_t dt_ns)>;

  /// Creates the DDS participant `name` and the clock's readers. Throws ConfigError.
  DownforceReader(const DdsSettings& settings, const std::string& name);
  ~DownforceReader();
  DownforceReader(const DownforceReader&) = delete;
  DownforceReader& operator=(const DownforceReader&) = delete;

  /// Waits for the run and calls `on_sample` for every AdhesionForce sample until the run's
  /// Stop has come (true; the samples received by then are handed on first) or `quit` is set
  /// (false). The last step's sample is never seen: thermo writes a stamp only when a roster
  /// member reads it, and nobody reads the last one (the recorder has it in its record batch).
  bool follow(const OnSample& on_sample, const std::atomic<bool>& quit);

 private:
  struct Endpoints;

  std::unique_ptr<Endpoints> endpoints_;
};

}  // namespace climbsim::downforce_log
