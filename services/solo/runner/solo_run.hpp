#pragma once
/// @file
/// `climbsim solo`: every model of the default composition (deploy/compose.yaml: scene,
/// sealing, thermo, drive, controller, recorder) in one process, on one thread, with no DDS
/// (docs/design.md#processes). Each service is configured by its own configure function (the
/// one its main calls), each model runs behind the same node class and the same IDL translators
/// as its service and is stepped by the one stepper (SoloParticipant) with the schedule (period,
/// offset) the launcher gives it, reading its inputs at the stamps the lockstep gives
/// (StampedTopic: zero-order hold, no same-step data). It writes the run directory the recorder
/// writes (scenario.yaml, trace.csv, summary.json, run.mcap, pictures/), and the same scenario
/// gives the same trace.csv, byte for byte, and the same run.mcap messages as `climbsim run`.

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace climbsim::solo {

/// What a solo run needs.
struct SoloOptions {
  std::string scenario_file;           ///< deploy/scenarios/*.yaml (as given; a name is resolved by the caller)
  std::vector<std::string> overrides;  ///< --set KEY=VALUE
  std::string out_dir;                 ///< run directory (created)
  std::string build_dir;               ///< for the scenario's $BUILD/ paths
  /// false (--no-mcap): no run.mcap (many variants of a sweep, or measuring what recording costs).
  bool mcap = true;
  /// Set (e.g. from a signal handler) to stop after the step under way: outcome "stopped".
  const std::atomic<bool>* stop = nullptr;
};

/// How a solo run ended, as summary.json says.
struct SoloResult {
  std::string outcome;       ///< completed, fell, stopped or failed (end_on.seal_over_nothing)
  std::string reason;        ///< as the clock's Stop would give it
  int exit_code = 0;         ///< ExitCode: 0, kExitFell, kExitStopped, kExitFailed
  std::uint64_t steps = 0;   ///< rows written
  double sim_s = 0.0;        ///< simulated time [s]
  double wall_s = 0.0;       ///< wall time of the stepping (not loading, not plotting) [s]
};

/// Loads and validates the scenario (ConfigError: one line naming file, key and value; the
/// controller type `external` is refused, no client can join a solo run), writes the resolved
/// scenario.yaml into out_dir, runs every step and writes trace.csv and summary.json (the keys
/// of a distributed run's, wheels_over_nothing too: the drive service's wheel check runs here).
/// Ends as the distributed run does: at a fall (end_on.fall), and failed at a seal over nothing
/// (end_on.seal_over_nothing), with the reason the clock would give. Plots are the caller's
/// (writeRunPlots).
SoloResult runSolo(const SoloOptions& options);

}  // namespace climbsim::solo
