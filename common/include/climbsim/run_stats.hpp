#pragma once
/// @file
/// What a process spent on a run, for the benchmarks: named counters and timers kept per
/// process and written as JSON to $CLIMBSIM_STATS_DIR/<participant>.json at its end (only
/// when that variable is set; `bench: e2e:` sets it). Cheap enough for every step.

#include <chrono>
#include <cstdint>
#include <string>

namespace climbsim {

/// Adds `value` to the process-wide counter `key` (e.g. "deliveries", "depth_render_s").
void statsAdd(const std::string& key, double value);

/// Adds the seconds since construction to the counter `key` when destroyed, and counts
/// one more event under `key + "_n"`.
class StatsTimer {
 public:
  explicit StatsTimer(const char* key) : key_(key), start_(std::chrono::steady_clock::now()) {}
  ~StatsTimer();
  StatsTimer(const StatsTimer&) = delete;
  StatsTimer& operator=(const StatsTimer&) = delete;

 private:
  const char* key_;
  std::chrono::steady_clock::time_point start_;
};

/// Like StatsTimer, but counts the CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID):
/// what a piece of work costs, without the time it spends blocked.
class StatsCpuTimer {
 public:
  explicit StatsCpuTimer(const char* key);
  ~StatsCpuTimer();
  StatsCpuTimer(const StatsCpuTimer&) = delete;
  StatsCpuTimer& operator=(const StatsCpuTimer&) = delete;

 private:
  const char* key_;
  double start_s_;
};

/// Logs the samples this process dropped over the run (malformed or out of range: logged,
/// counted and dropped, docs/design.md#layout) as one line "dropped_samples=N (detail)". The
/// launcher reads that token from every service's output (also from other hosts) and sums them into
/// summary.json's dropped_samples. Call once, after the run.
void logDroppedSamples(std::uint64_t count, const std::string& detail);

/// CPU time of the calling thread [s].
double threadCpuSeconds();

/// CPU time of the whole process, every thread (DDS's included) [s].
double processCpuSeconds();

/// Writes every counter to $CLIMBSIM_STATS_DIR/<name>.json if the variable is set; a
/// failure to write is logged, never thrown (statistics never fail a run).
void writeStatsIfAsked(const std::string& name);

}  // namespace climbsim
