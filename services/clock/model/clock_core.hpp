#pragma once
/// @file
/// The lockstep simulation clock (DESIGN.md §2) as a pure state machine: events in,
/// messages out through a ClockTransport, wall time passed in by the caller. No DDS.

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "clock_messages.hpp"
#include "pacing.hpp"

namespace climbsim::clock {

/// Configuration of one run of the clock.
struct ClockParams {
  std::vector<std::string> roster;       ///< required participants, unique names
  std::int64_t dt_ns = 5'000'000;        ///< step length [ns], > 0
  std::uint64_t end_step = 1000;         ///< steps 0..end_step-1 are run; >= 1
  double realtime_factor = 0.0;          ///< 0 = as fast as possible, 1 = wall-clock paced
  std::chrono::milliseconds start_timeout{30000};  ///< whole roster ready and armed within this
  std::chrono::milliseconds step_timeout{10000};   ///< watchdog: every due participant done within this
  bool start_paused = false;             ///< start paused at step 0 (resume or single-step to go on)
  std::uint64_t run_id = 1;              ///< tells this run's messages from another's

  /// Throws ConfigError naming the parameter and value: empty or duplicate roster names,
  /// invalid names, dt_ns <= 0, end_step == 0, negative or non-finite realtime_factor,
  /// non-positive timeouts.
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

  /// Does what is due at `now` (grants, pacing, timeouts, end) and returns the latest
  /// time at which poll() must be called again if no event comes first.
  Time poll(Time now);

  ClockPhase phase() const { return phase_; }
  bool finished() const { return phase_ == ClockPhase::kFinished; }
  bool paused() const { return paused_; }
  /// The next step to be granted.
  std::uint64_t nextStep() const { return next_step_; }
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
  void reanchor(Time now);
  void publishSimTime(bool paused);
  bool onRoster(const std::string& name) const;
  std::uint64_t lastGrantedStep() const;

  ClockParams params_;
  ClockTransport& transport_;
  ClockPhase phase_ = ClockPhase::kWaitingForReady;
  Time start_deadline_{};
  std::map<std::string, ReadyMsg> ready_;                    ///< by participant
  std::map<std::string, std::pair<std::string, std::string>> idl_first_;  ///< file -> {participant, hash}
  std::set<std::string> armed_;
  std::set<std::string> pending_;                            ///< due at granted_step_, not done yet
  std::optional<std::uint64_t> granted_step_;
  Time granted_at_{};
  std::uint64_t next_step_ = 0;
  bool paused_ = false;
  std::uint64_t single_steps_left_ = 0;
  Time next_pause_announce_{};  ///< while paused, SimTime is repeated at this period
  bool stop_requested_ = false;
  std::string stop_requested_by_;
  double realtime_factor_ = 0.0;
  PacingAnchor anchor_{};
  std::optional<StopMsg> stop_;
  int exit_code_ = 0;
};

}  // namespace climbsim::clock
