#pragma once
/// @file
/// Runs the processes of one composition: starts them with their output on pipes, copies
/// the output line by line, records exits in state.json, and ends the run in order
/// (grace period, SIGTERM, SIGKILL) once the clock has ended or a stop was requested.

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/run_summary/summary_additions.hpp"
#include "climbsim/run_summary/summary_from_trace.hpp"
#include "launch_plan.hpp"
#include "output_router.hpp"
#include "run_exit_code.hpp"
#include "run_state.hpp"
#include "signal_events.hpp"
#include "trace_progress.hpp"

namespace climbsim::launcher {

/// How a supervisor behaves.
struct SupervisorOptions {
  bool to_terminal = true;                     ///< copy output to stdout, prefixed (foreground)
  bool color = false;                          ///< color the prefixes
  bool shield_interrupt = true;                ///< started programs ignore the terminal's Ctrl-C
  std::vector<std::string> extra_log_dirs;     ///< also write <dir>/<process>.log (run --out)
  std::chrono::milliseconds grace{5000};       ///< how long the others may take to end after the clock
  std::chrono::milliseconds term_wait{5000};   ///< from SIGTERM to SIGKILL
  std::chrono::milliseconds stop_wait{10000};  ///< from a stop request (clock asked) to SIGTERM
  /// A process stopped (SIGSTOP, a debugger) this long is taken as failed: its process exists
  /// but does not run, so it can neither compute nor end; it is killed at once.
  std::chrono::milliseconds stopped_limit{500};
  /// The trace the recorder writes (trace_progress.hpp); empty: no progress is shown.
  std::string progress_trace;
  double progress_duration_s = 0.0;            ///< the run's simulated duration [s] (0: unknown)
  /// Live status line on the terminal (a tty) every 0.5 s; otherwise a progress log line
  /// every `progress_log_every`.
  bool progress_live = false;
  std::chrono::milliseconds progress_log_every{10000};
};

/// Supervises one run. Needs the process's SignalEvents for stop requests and child exits.
class Supervisor {
 public:
  /// `state` is the run state to keep up to date in paths.state_file.
  Supervisor(LaunchPlan plan, RunPaths paths, RunState state, SupervisorOptions options, SignalEvents& signals);
  ~Supervisor();

  /// Opens the log files and starts every process, the clock first. Throws
  /// std::runtime_error naming the program if one cannot start (those started are killed).
  void start();

  /// Supervises until every process has ended. The exit code of the run (runExitCode): 2 if
  /// a process refused its configuration, else the clock's if it is not 0, else 1 if a service
  /// failed, else 0.
  int wait();

  /// Each process's name and exit code, the clock first; observers left out (they never decide
  /// how a run ended).
  std::vector<ProcessEnd> processEnds() const;

  /// The first service (not the clock) that exited with a non-zero code, if any.
  const std::optional<run_summary::FailedProcess>& firstFailure() const { return first_failure_; }
  /// ": service 'drive' (pid 123) was stopped (SIGSTOP or a debugger) ..." when a stopped
  /// process ended the run, else "": for the launcher's final line.
  const std::string& stoppedNote() const { return stopped_note_; }
  /// What each process said it dropped ("dropped_samples=N" in its output), by process name.
  const std::map<std::string, std::uint64_t>& droppedSamples() const { return dropped_; }
  /// The drive's "wheel N stands over nothing at t = T s" lines, in the order they came.
  const std::vector<run_summary::WheelOverNothing>& wheelsOverNothing() const { return wheels_over_nothing_; }
  /// The reason of the clock's "run failed: REASON" line, "" if it printed none.
  const std::string& clockFailure() const { return clock_failure_; }
  /// Where the run's viewer serves its page (its "open http://..." line), "" until it said so.
  const std::string& viewerAddress() const { return viewer_address_; }

 private:
  struct Managed;
  using TimePoint = std::chrono::steady_clock::time_point;

  void pollOnce();
  void readOutput(Managed& process, bool until_end);
  void reapExits();
  void onExit(Managed& process, int code);
  void onStopRequest(int signal_number);
  void stopTheClock(const std::string& why);
  void applyDeadlines();
  void checkStopped();
  void signalRunning(int signal_number, const std::string& why);
  bool everyoneEnded() const;
  int exitCode() const;
  void saveState();
  void showProgress(bool final_word);
  std::string runStateText() const;

  LaunchPlan plan_;
  RunPaths paths_;
  RunState state_;
  SupervisorOptions options_;
  SignalEvents& signals_;
  std::unique_ptr<OutputRouter> output_;
  std::vector<std::unique_ptr<Managed>> processes_;
  int stop_requests_ = 0;
  std::optional<TimePoint> stop_clock_at_;
  std::optional<TimePoint> term_at_;
  std::optional<TimePoint> kill_at_;
  std::string stop_clock_reason_;
  std::unique_ptr<TraceTail> trace_;
  TimePoint next_progress_{};
  std::optional<std::pair<TimePoint, double>> first_row_;  ///< wall time and t_s of the first row seen
  RateMeter rate_;  ///< the rows' real-time factor (wall seconds since first_row_)
  std::optional<run_summary::FailedProcess> first_failure_;
  std::string stopped_note_;
  std::map<std::string, std::uint64_t> dropped_;
  std::vector<run_summary::WheelOverNothing> wheels_over_nothing_;
  std::string clock_failure_;
  std::string viewer_address_;
  TimePoint next_stopped_check_{};
};

}  // namespace climbsim::launcher
