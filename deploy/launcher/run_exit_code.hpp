#pragma once
/// @file
/// The exit code of a whole run from the exit codes of its processes, and summary.json made to
/// agree with it. Bad input is exit code 2 wherever it is found: a service that refuses its
/// configuration (it exits kExitConfig, e.g. a sealing shard reading from a producer that is not
/// on the roster, found before step 0) makes the run exit 2, although the clock, which only saw
/// a participant fail, exits 1.

#include <optional>
#include <string>
#include <vector>

namespace climbsim::launcher {

/// One process's end: its name and exit code (none: it did not end, counted as failed).
struct ProcessEnd {
  std::string name;
  std::optional<int> exit_code;
};

/// The run's exit code: kExitConfig (2) if the clock or any service exited with it; else the
/// clock's code if it is not 0; else 1 if a service failed; else 0. `clock` is processes[0].
int runExitCode(const std::vector<ProcessEnd>& processes);

/// The first service (not the clock, processes[0]) that exited with kExitConfig, if any.
std::optional<std::string> configCulprit(const std::vector<ProcessEnd>& processes);

/// The order in which to take the services found ended in one look (their exit codes in the
/// composition's order): those a signal ended (exit code above 128: a crash, a kill) first,
/// then the others, each group in the composition's order. A process a signal ended ended by
/// itself; one that exited on its own may have done so because the clock told it that the run
/// had failed, which it can do within milliseconds of a kill, before the launcher looks. Taken
/// in the composition's order, a service listed before the killed one would be named instead.
std::vector<std::size_t> blameOrder(const std::vector<int>& exit_codes);

/// Starts of a secured run in all, when its participants give up starts whose DDS Security
/// handshake stalled (Fast DDS 2.9.1 leaves a pair of participants unauthenticated now and
/// then; they exit kExitRetryStart before step 0). About one start in five stalls on a 2-core
/// machine, and three in a row have been seen; each stalled start costs about 6 s, 5 s of it the
/// wait for the handshake.
constexpr int kMaxStarts = 6;

/// True if the run whose `starts` (1, 2, ...) start ended with `processes` is to be started
/// again: it is `secured`, some process gave the start up with kExitRetryStart, and fewer
/// than kMaxStarts starts were made. An unsecured run has no handshakes to stall.
bool startAgain(const std::vector<ProcessEnd>& processes, bool secured, int starts);

/// Makes out_dir/summary.json agree with the launcher's exit code `exit_code` when that is
/// kExitConfig and the summary says otherwise (the recorder took the clock's "failed", 1):
/// exit_code 2, outcome failed, completed false, and the culprit `culprit` if the summary names
/// none. Returns whether it changed the file. Nothing if there is no summary.json; never throws.
bool agreeOnConfigError(const std::string& out_dir, int exit_code, const std::string& culprit);

}  // namespace climbsim::launcher
