#pragma once
/// @file
/// The simulation clock (docs/design.md#the-shared-simulation-clock) as a pure state machine:
/// events in, messages out through a ClockTransport, wall time passed in by the caller. No DDS.
///
/// Horizon protocol: the stamped data are the promise, the clock only bounds the run-ahead.
/// It grants a horizon H ("compute every due step k < H"),
///   H = min(end_step, min_p progress_p + W, pause limit, paced limit),
/// where progress_p is the step below which participant p has done every due step (it
/// acknowledges it in batches). W = 1 is the classic one-grant-per-step lockstep; every W
/// gives the same trace because every input is stamped with an earlier step.

#include <chrono>
#include <cstdint>
#include <map>
#include <utility>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "clock_messages.hpp"
#include "control_senders.hpp"
#include "pacing.hpp"

namespace climbsim::clock {

/// The default horizon window W [steps] (`bench: e2e:` measured it best; docs/design.md#horizons).
inline constexpr std::uint32_t kDefaultWindowSteps = 16;

/// Configuration of one run of the clock.
struct ClockParams {
  std::vector<std::string> roster;       ///< required participants, unique names
  std::int64_t dt_ns = 5'000'000;        ///< step length [ns], > 0
  std::uint64_t end_step = 1000;         ///< steps 0..end_step-1 are run; >= 1
  std::uint32_t window_steps = 1;        ///< W: horizon ahead of the slowest participant, >= 1
  /// Largest W the step-data queues hold (QoS history depth - 2); 0 = not checked.
  std::uint32_t max_window_steps = 0;
  /// IDL file hashes the clock was built from ({file, sha256}); a participant built from
  /// another text of one of these files is refused (an old protocol cannot join).
  std::vector<std::pair<std::string, std::string>> idl_hashes;
  double realtime_factor = 0.0;          ///< 0 = as fast as possible, 1 = wall-clock paced
  std::chrono::milliseconds start_timeout{30000};  ///< whole roster ready and armed within this
  std::chrono::milliseconds step_timeout{10000};   ///< watchdog: every due participant done within this
  bool start_paused = false;             ///< start paused at step 0 (resume or single-step to go on)
  /// A pause nobody resumes (or single-steps) within this ends the run as stopped, with
  /// the reason; none: a pause may last for ever (compose clock.max_pause_s).
  std::optional<std::chrono::milliseconds> max_pause;
  std::uint64_t run_id = 1;              ///< tells this run's messages from another's
  /// Who may send ClockControl (checked by the node against discovery); none: anybody.
  std::optional<std::vector<ControlSender>> control_senders;

  /// Throws ConfigError naming the parameter and value: empty or duplicate roster names,
  /// invalid names, dt_ns <= 0, end_step == 0, negative or non-finite realtime_factor,
  /// non-positive timeouts, window_steps < 1 or above max_window_steps.
  void validate() const;
};

/// Where the clock's messages go (DDS writers in the node, a recorder in unit tests).
class ClockTransport {
 public:
  virtual ~ClockTransport() = default;
  virtual void publishRunStart(const RunStartMsg& msg) = 0;
  virtual void publishGrant(const GrantMsg& msg) = 0;
  virtual void publishStop(const StopMsg& msg) = 0;
  virtual void publishSimTime(const SimTimeMsg& msg) = 0;
  /// Readers matched to the grant writer; step 0 waits for one per roster participant.
  virtual int grantReaders() const = 0;
};

/// The clock's life: waiting for every ready, waiting for every armed, running, finished.
enum class ClockPhase { kWaitingForReady, kArming, kRunning, kFinished };

/// The lockstep clock. Single-threaded: call the on*() events and poll() from one thread.
class ClockCore {
 public:
  using Time = WallClock::time_point;

  /// Validates params (ConfigError).
  ClockCore(ClockParams params, ClockTransport& transport);

  /// Starts the start timeout.
  void start(Time now);

  void onReady(const ReadyMsg& msg, Time now);
  void onDone(const DoneMsg& msg, Time now);
  void onControl(const ControlMsg& msg, Time now);
  /// A roster participant's process vanished (`how`: "liveliness lost", "left", ...).
  void onParticipantLost(const std::string& participant, const std::string& how, Time now);
  /// Before the run starts, the clock cannot reach roster participant `participant` (their
  /// DDS Security handshake stalled; `reason` says so): the run fails naming it, with exit code
  /// kExitRetryStart, since nothing was computed and it can start again. Ignored once running.
  void onStartStalled(const std::string& participant, const std::string& reason);

  /// Does what is due at `now` (grants, pacing, timeouts, end) and returns the latest
  /// time at which poll() must be called again if no event comes first.
  Time poll(Time now);

  ClockPhase phase() const { return phase_; }
  bool finished() const { return phase_ == ClockPhase::kFinished; }
  bool paused() const { return paused_; }
  /// The horizon granted so far: every due step below it may be computed (0: none yet).
  std::uint64_t horizon() const { return horizon_; }
  /// The step every roster participant has reached (min progress; 0 before the run).
  std::uint64_t reachedStep() const;
  /// The clock's view of a participant's progress (its last acknowledgement).
  std::uint64_t progressOf(const std::string& participant) const;
  /// The Stop message once finished.
  const std::optional<StopMsg>& stopMessage() const { return stop_; }
  /// Process exit code once finished (climbsim::ExitCode).
  int exitCode() const { return exit_code_; }
  /// Roster participants due at `step`, sorted by name (needs the roster ready).
  std::vector<std::string> dueAt(std::uint64_t step) const;
  /// Roster participants that have not announced ready, sorted.
  std::vector<std::string> missingReady() const;

 private:
  void fail(int exit_code, const std::string& culprit, const std::string& reason);
  void finish(StopKind kind, int exit_code, const std::string& culprit, const std::string& reason);
  void startRun();
  std::optional<std::string> zeroLagCycle() const;
  void reanchor(Time now);
  void publishSimTime(bool paused);
  bool onRoster(const std::string& name) const;
  std::uint64_t horizonTarget(Time now) const;
  void grant(std::uint64_t horizon, Time now);
  bool watchdogExpired(Time now);
  std::string watchdogCulprits(std::vector<std::string>& names) const;

  ClockParams params_;
  ClockTransport& transport_;
  ClockPhase phase_ = ClockPhase::kWaitingForReady;
  Time start_deadline_{};
  std::map<std::string, ReadyMsg> ready_;                    ///< by participant
  std::map<std::string, std::pair<std::string, std::string>> idl_first_;  ///< file -> {participant, hash}
  std::set<std::string> armed_;
  std::map<std::string, std::uint64_t> progress_;           ///< by participant: all due steps below done
  std::uint64_t horizon_ = 0;                                ///< granted horizon (published)
  std::uint64_t reached_ = 0;                                ///< min progress at the last change
  Time reached_at_{};                                        ///< when the min progress last grew
  bool paused_ = false;
  std::uint64_t pause_limit_ = 0;                            ///< while paused: the horizon may reach this
  Time next_pause_announce_{};  ///< while paused, SimTime is repeated at this period
  /// A new horizon publishes SimTime only this long after the last one (observers draw at most
  /// 30 frames a second; at 5x real time a horizon comes about 125 times a second).
  static constexpr std::chrono::nanoseconds kSimTimePeriod{33'333'333};
  std::optional<Time> last_sim_time_;  ///< when SimTime last went out with a horizon
  Time paused_since_{};         ///< last pause, single step, or the run start if it started paused
  bool stop_requested_ = false;
  std::optional<std::pair<std::string, std::string>> fell_;  ///< {participant, reason} of a fall
  std::string stop_requested_by_;
  double realtime_factor_ = 0.0;
  PacingAnchor anchor_{};
  std::optional<StopMsg> stop_;
  int exit_code_ = 0;
};

}  // namespace climbsim::clock
