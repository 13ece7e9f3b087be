#include "climbsim/leave_after_results.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace climbsim {

namespace {

char g_line[256];
std::size_t g_line_size = 0;
char g_late_line[256];
std::size_t g_late_line_size = 0;
char g_term_line[256];
std::size_t g_term_line_size = 0;
volatile sig_atomic_t g_exit_code = 0;
bool g_results_complete = false;

/// Async-signal-safe: write(2) and _exit(2) only.
void onAbortAfterResults(int) {
  ssize_t ignored = ::write(STDERR_FILENO, g_line, g_line_size);
  (void)ignored;
  ::_exit(g_exit_code);
}

/// The leave outlasted its deadline (SIGALRM). Async-signal-safe as above.
void onLeaveTooLong(int) {
  ssize_t ignored = ::write(STDERR_FILENO, g_late_line, g_late_line_size);
  (void)ignored;
  ::_exit(g_exit_code);
}

/// Asked to end (SIGTERM, the launcher's grace after the clock ended) while leaving: nothing
/// but the leave remains. Async-signal-safe as above.
void onTermWhileLeaving(int) {
  ssize_t ignored = ::write(STDERR_FILENO, g_term_line, g_term_line_size);
  (void)ignored;
  ::_exit(g_exit_code);
}

std::size_t lineSize(int written, std::size_t capacity) {
  return written < 0 ? 0 : std::min(static_cast<std::size_t>(written), capacity - 1);
}

}  // namespace

void leaveAfterResults(const char* name, int exit_code, unsigned leave_deadline_s) {
  char short_name[64];
  std::strncpy(short_name, name, sizeof short_name - 1);
  short_name[sizeof short_name - 1] = '\0';
  const int written = std::snprintf(
      g_line, sizeof g_line,
      "%s: Fast DDS aborted while the participants left after the run; the results were complete "
      "(exit code %d)\n",
      short_name, exit_code);
  g_line_size = lineSize(written, sizeof g_line);
  const int late = std::snprintf(g_late_line, sizeof g_late_line,
                                 "%s: Fast DDS did not let the participant leave within %u s after the run; the "
                                 "results were complete (exit code %d)\n",
                                 short_name, leave_deadline_s, exit_code);
  g_late_line_size = lineSize(late, sizeof g_late_line);
  const int term = std::snprintf(g_term_line, sizeof g_term_line,
                                 "%s: asked to end (SIGTERM) while its participant left DDS after the run; the "
                                 "results were complete (exit code %d)\n",
                                 short_name, exit_code);
  g_term_line_size = lineSize(term, sizeof g_term_line);
  g_exit_code = exit_code;
  struct sigaction action {};
  action.sa_handler = onAbortAfterResults;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGABRT, &action, nullptr);
  struct sigaction late_action {};
  late_action.sa_handler = onLeaveTooLong;
  sigemptyset(&late_action.sa_mask);
  ::sigaction(SIGALRM, &late_action, nullptr);
  struct sigaction term_action {};
  term_action.sa_handler = onTermWhileLeaving;
  sigemptyset(&term_action.sa_mask);
  ::sigaction(SIGTERM, &term_action, nullptr);
  ::alarm(leave_deadline_s);
  g_results_complete = true;
}

bool resultsComplete() { return g_results_complete; }

}  // namespace climbsim
