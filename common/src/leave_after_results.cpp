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
volatile sig_atomic_t g_exit_code = 0;

/// Async-signal-safe: write(2) and _exit(2) only.
void onAbortAfterResults(int) {
  ssize_t ignored = ::write(STDERR_FILENO, g_line, g_line_size);
  (void)ignored;
  ::_exit(g_exit_code);
}

}  // namespace

void leaveAfterResults(const char* name, int exit_code) {
  char short_name[64];
  std::strncpy(short_name, name, sizeof short_name - 1);
  short_name[sizeof short_name - 1] = '\0';
  const int written = std::snprintf(
      g_line, sizeof g_line,
      "%s: Fast DDS aborted while the participants left after the run; the results were complete "
      "(exit code %d)\n",
      short_name, exit_code);
  g_line_size = written < 0 ? 0 : std::min(static_cast<std::size_t>(written), sizeof g_line - 1);
  g_exit_code = exit_code;
  struct sigaction action {};
  action.sa_handler = onAbortAfterResults;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGABRT, &action, nullptr);
}

}  // namespace climbsim
