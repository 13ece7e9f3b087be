#include "detach.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace climbsim::launcher {

void DetachReport::send(const std::string& text) {
  if (fd_ < 0) {
    return;
  }
  (void)!::write(fd_, text.data(), text.size());
  ::close(fd_);  // the starting process sees the end of the report and returns
  fd_ = -1;
}

void DetachReport::ready() { send("ready\n"); }

void DetachReport::failed(int exit_code, const std::string& message) {
  send("failed " + std::to_string(exit_code) + " " + message + "\n");
}

namespace {
[[noreturn]] void becomeDaemon(const std::string& log_file, int report_fd,
                               const std::function<int(DetachReport&)>& daemon_body) {
  ::setsid();
  const pid_t grandchild = ::fork();
  if (grandchild != 0) {
    ::_exit(grandchild < 0 ? 1 : 0);  // the session leader goes, so no terminal can be acquired
  }
  // Lead a process group of our own: the started programs join it, and `down` can signal
  // the whole run at once.
  ::setpgid(0, 0);
  const int null_fd = ::open("/dev/null", O_RDONLY);
  const int log_fd = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
  if (null_fd >= 0) {
    ::dup2(null_fd, STDIN_FILENO);
    ::close(null_fd);
  }
  if (log_fd >= 0) {
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    ::close(log_fd);
  }
  DetachReport report(report_fd);
  int code = 1;
  try {
    code = daemon_body(report);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    report.failed(1, e.what());
  }
  report.failed(1, "the supervisor ended before the services were up; see " + log_file);  // no-op after a report
  spdlog::default_logger()->flush();
  std::fflush(nullptr);
  ::_exit(code);
}
}  // namespace

int runDetached(const std::string& log_file, const std::function<int(DetachReport&)>& daemon_body) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
  }
  spdlog::default_logger()->flush();
  std::fflush(nullptr);  // buffered output would otherwise be written twice
  const pid_t child = ::fork();
  if (child < 0) {
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    becomeDaemon(log_file, fds[1], daemon_body);
  }
  ::close(fds[1]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  std::string report;
  char buffer[512];
  while (true) {
    const ssize_t got = ::read(fds[0], buffer, sizeof(buffer));
    if (got > 0) {
      report.append(buffer, static_cast<std::size_t>(got));
    } else if (got == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  if (report.rfind("ready", 0) == 0) {
    return 0;
  }
  if (report.rfind("failed ", 0) == 0) {
    std::size_t end = 0;
    const int code = std::stoi(report.substr(7), &end);
    std::string message = report.substr(7 + end);
    const auto first = message.find_first_not_of(' ');
    const auto last = message.find_last_not_of('\n');
    message = first == std::string::npos || last == std::string::npos ? "" : message.substr(first, last - first + 1);
    spdlog::error("{}", message);
    return code;
  }
  spdlog::error("the detached supervisor ended without a report; see {}", log_file);
  return 1;
}

}  // namespace climbsim::launcher
