#pragma once
/// The last act of a service: leaving the DDS domain once its results are complete.
///
/// Every participant of a run leaves at the same moment when the run ends. Fast DDS 2.9 then
/// now and then aborts in its lease check of a remote participant that is leaving at that very
/// moment (PDP::check_remote_participant_liveliness asserts on a proxy that the removal has
/// just returned to its pool): SIGABRT in a process whose run is over and whose results are
/// written. leaveAfterResults() marks that point: an abort after it ends the process with the
/// exit code the run gave and one line on stderr saying so, instead of a crash the launcher
/// would count as the service dying. An abort before it (during the run) stays a crash.

namespace climbsim {

/// How long leaving DDS may take once the results are complete [s]. Fast DDS 2.9 now and then
/// deadlocks there too (a writer's destructor waits for its event thread, which waits for the
/// discovery mutex that a thread removing a leaving participant holds): a process still there
/// after this ends with the run's exit code and one line saying so, rather than hanging the run.
/// So does a process asked to end (SIGTERM) while it leaves: the launcher sends it to whoever
/// is still there a few seconds after the clock ended, which is sooner than this deadline.
constexpr unsigned kLeaveDeadline_s = 15;

/// Marks this process's results as complete (outputs written, statistics saved, dropped samples
/// logged) with `exit_code`: only leaving DDS remains. `name` (copied, at most 63 characters)
/// names the process in the line an abort from here on, a leave that lasts longer than
/// `leave_deadline_s`, or a SIGTERM during the leave, prints; each ends the process with
/// `exit_code`. Call once, after the run.
void leaveAfterResults(const char* name, int exit_code, unsigned leave_deadline_s = kLeaveDeadline_s);

/// Whether leaveAfterResults() was called in this process: its results are complete, and once
/// its participant has left, nothing but static teardown remains (guardedMain then ends the
/// process without it: Fast DDS's participant factory sleeps 100 ms in its destructor).
bool resultsComplete();

}  // namespace climbsim
