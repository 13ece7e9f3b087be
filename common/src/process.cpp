#include "climbsim/process.hpp"

#include <sys/resource.h>
#include <sys/time.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace climbsim {

int exitCodeFromStatus(int status) {
  if (WIFEXITED(status)) {
    return WEXITSTATUS(status);
  }
  if (WIFSIGNALED(status)) {
    return 128 + WTERMSIG(status);
  }
  return -1;
}

ChildProcess::ChildProcess(const ProcessSpec& spec) {
  if (spec.argv.empty()) {
    throw std::runtime_error("cannot start a process without argv");
  }
  int out_fd = spec.output_fd;
  if (!spec.output_file.empty()) {
    out_fd = ::open(spec.output_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (out_fd < 0) {
      throw std::runtime_error("cannot open '" + spec.output_file + "': " + std::strerror(errno));
    }
  }
  // An exec failure is reported through this pipe (closed on a successful exec).
  int status_pipe[2];
  if (::pipe2(status_pipe, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
  }
  std::vector<char*> argv;
  for (const auto& a : spec.argv) {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  pid_ = ::fork();
  if (pid_ < 0) {
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid_ == 0) {
    if (spec.die_with_parent) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) {
        ::_exit(127);
      }
    }
    if (out_fd >= 0) {
      ::dup2(out_fd, STDOUT_FILENO);
      ::dup2(out_fd, STDERR_FILENO);
    }
    int devnull = ::open("/dev/null", O_RDONLY);
    if (devnull >= 0) {
      ::dup2(devnull, STDIN_FILENO);
    }
    for (const auto& [key, value] : spec.env) {
      ::setenv(key.c_str(), value.c_str(), 1);
    }
    ::execvp(argv[0], argv.data());
    const int err = errno;
    (void)!::write(status_pipe[1], &err, sizeof(err));
    ::_exit(127);
  }
  ::close(status_pipe[1]);
  if (!spec.output_file.empty()) {
    ::close(out_fd);
  }
  int err = 0;
  const auto got = ::read(status_pipe[0], &err, sizeof(err));
  ::close(status_pipe[0]);
  if (got == static_cast<ssize_t>(sizeof(err))) {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    throw std::runtime_error("cannot start '" + spec.argv[0] + "': " + std::strerror(err));
  }
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(other.pid_),
      exit_code_(other.exit_code_),
      cpu_seconds_(other.cpu_seconds_),
      context_switches_(other.context_switches_) {
  other.pid_ = -1;
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !poll()) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::optional<int> ChildProcess::poll() {
  if (exit_code_ || pid_ <= 0) {
    return exit_code_;
  }
  int status = 0;
  struct rusage usage {};
  const pid_t done = ::wait4(pid_, &status, WNOHANG, &usage);
  if (done == pid_) {
    exit_code_ = exitCodeFromStatus(status);
    const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * t.tv_usec; };
    cpu_seconds_ = seconds(usage.ru_utime) + seconds(usage.ru_stime);
    context_switches_ = static_cast<std::uint64_t>(usage.ru_nvcsw) + static_cast<std::uint64_t>(usage.ru_nivcsw);
  }
  return exit_code_;
}

std::optional<int> ChildProcess::waitFor(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  // waitpid has no timeout; poll at a period far below any deadline we check.
  while (!poll()) {
    if (std::chrono::steady_clock::now() >= deadline) {
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return exit_code_;
}

void ChildProcess::signal(int signal_number) {
  if (pid_ > 0 && !poll()) {
    ::kill(pid_, signal_number);
  }
}

}  // namespace climbsim
