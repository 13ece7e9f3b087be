#include "signal_events.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace climbsim::launcher {

namespace {
int g_write_fd = -1;
int g_read_fd = -1;
constexpr int kHandled[] = {SIGCHLD, SIGINT, SIGTERM, SIGHUP, SIGPIPE};

void onSignal(int signal_number) {
  const int saved_errno = errno;
  const auto byte = static_cast<unsigned char>(signal_number);
  (void)!::write(g_write_fd, &byte, 1);  // a full pipe already holds a wake-up
  errno = saved_errno;
}

void install(int signal_number, void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  ::sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | (signal_number == SIGCHLD ? SA_NOCLDSTOP : 0);
  ::sigaction(signal_number, &action, nullptr);
}
}  // namespace

SignalEvents::SignalEvents() {
  if (g_write_fd >= 0) {
    throw std::logic_error("SignalEvents exists already");
  }
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC | O_NONBLOCK) != 0) {
    throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
  }
  g_read_fd = fds[0];
  g_write_fd = fds[1];
  for (const int s : kHandled) {
    install(s, onSignal);
  }
}

SignalEvents::~SignalEvents() {
  for (const int s : kHandled) {
    install(s, SIG_DFL);
  }
  ::close(g_read_fd);
  ::close(g_write_fd);
  g_read_fd = g_write_fd = -1;
}

int SignalEvents::fd() const { return g_read_fd; }

std::vector<int> SignalEvents::drain() {
  std::vector<int> requests;
  unsigned char buffer[64];
  while (true) {
    const ssize_t got = ::read(g_read_fd, buffer, sizeof(buffer));
    if (got <= 0) {
      break;
    }
    for (ssize_t i = 0; i < got; ++i) {
      if (buffer[i] == SIGINT || buffer[i] == SIGTERM || buffer[i] == SIGHUP) {
        requests.push_back(buffer[i]);
      }
    }
  }
  return requests;
}

SignalEvents::InterruptShield::InterruptShield() { install(SIGINT, SIG_IGN); }

SignalEvents::InterruptShield::~InterruptShield() {
  install(SIGINT, g_write_fd >= 0 ? onSignal : SIG_DFL);
}

}  // namespace climbsim::launcher
