#include "climbsim/leave_after_results.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace climbsim {

namespace {

/// The line each signal prints once the results are complete, written before the handler is
/// installed (a handler may only write(2) and _exit(2)).
struct EndLine {
  int signal_number;
  char text[256];
  std::size_t size;
};
EndLine g_lines[] = {
    {SIGABRT, {}, 0},  // Fast DDS aborted while the participants left
    {SIGALRM, {}, 0},  // the leave outlasted its deadline
    {SIGTERM, {}, 0},  // asked to end (the launcher's grace after the clock ended) while leaving
};
volatile sig_atomic_t g_exit_code = 0;
bool g_results_complete = false;

/// Any of them: nothing but the leave remains. Async-signal-safe: write(2) and _exit(2) only.
void onSignalAfterResults(int signal_number) {
  for (const auto& line : g_lines) {
    if (line.signal_number == signal_number) {
      ssize_t ignored = ::write(STDERR_FILENO, line.text, line.size);
      (void)ignored;
    }
  }
  ::_exit(g_exit_code);
}

/// Formats the line of `signal_number` (printf-style `format`).
template <class... Args>
void setLine(int signal_number, const char* format, Args... args) {
  for (auto& line : g_lines) {
    if (line.signal_number != signal_number) continue;
    const int written = std::snprintf(line.text, sizeof line.text, format, args...);
    line.size = written < 0 ? 0 : std::min(static_cast<std::size_t>(written), sizeof line.text - 1);
  }
}

}  // namespace

void leaveAfterResults(const char* name, int exit_code, unsigned leave_deadline_s) {
  char short_name[64];
  std::strncpy(short_name, name, sizeof short_name - 1);
  short_name[sizeof short_name - 1] = '\0';
  setLine(SIGABRT,
          "%s: Fast DDS aborted while the participants left after the run; the results were complete "
          "(exit code %d)\n",
          short_name, exit_code);
  setLine(SIGALRM,
          "%s: Fast DDS did not let the participant leave within %u s after the run; the results were "
          "complete (exit code %d)\n",
          short_name, leave_deadline_s, exit_code);
  setLine(SIGTERM,
          "%s: asked to end (SIGTERM) while its participant left DDS after the run; the results were "
          "complete (exit code %d)\n",
          short_name, exit_code);
  g_exit_code = exit_code;
  for (const auto& line : g_lines) {
    struct sigaction action {};
    action.sa_handler = onSignalAfterResults;
    sigemptyset(&action.sa_mask);
    ::sigaction(line.signal_number, &action, nullptr);
  }
  ::alarm(leave_deadline_s);
  g_results_complete = true;
}

bool resultsComplete() { return g_results_complete; }

}  // namespace climbsim
