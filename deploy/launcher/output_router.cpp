#include "output_router.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace climbsim::launcher {

namespace {
constexpr const char* kColors[] = {"\033[36m", "\033[33m", "\033[32m", "\033[35m", "\033[34m",
                                   "\033[96m", "\033[93m", "\033[92m", "\033[95m", "\033[94m"};

/// Writes everything unless the descriptor fails (EPIPE, disk full): a log that cannot be
/// written must not stop the run.
bool writeAll(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t written = ::write(fd, data.data(), data.size());
    if (written < 0) {
      if (errno == EINTR) {
        continue;
      }
      return false;
    }
    data.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}
}  // namespace

bool terminalWantsColor() {
  const char* no_color = std::getenv("NO_COLOR");
  return ::isatty(STDOUT_FILENO) == 1 && (no_color == nullptr || *no_color == '\0');
}

std::string linePrefix(const std::string& name, std::size_t width, std::size_t index, bool color) {
  std::string prefix = name + std::string(width > name.size() ? width - name.size() : 0, ' ') + " | ";
  if (color) {
    prefix = kColors[index % std::size(kColors)] + prefix + "\033[0m";
  }
  return prefix;
}

OutputRouter::OutputRouter(const std::vector<std::string>& names, bool to_terminal, bool color)
    : to_terminal_(to_terminal) {
  std::size_t width = 0;
  for (const auto& n : names) {
    width = std::max(width, n.size());
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    targets_.push_back(Target{linePrefix(names[i], width, i, color), {}});
  }
}

OutputRouter::~OutputRouter() {
  for (auto& target : targets_) {
    for (const int fd : target.log_fds) {
      ::close(fd);
    }
  }
}

void OutputRouter::addLogFile(std::size_t index, const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot write the log file '" + path + "': " + std::strerror(errno));
  }
  targets_.at(index).log_fds.push_back(fd);
}

void OutputRouter::line(std::size_t index, std::string_view text) {
  auto& target = targets_.at(index);
  std::string buffer(text);
  buffer += '\n';
  for (const int fd : target.log_fds) {
    writeAll(fd, buffer);
  }
  if (!to_terminal_) {
    return;
  }
  eraseStatus();
  if (!writeAll(STDOUT_FILENO, target.prefix + buffer) && errno == EPIPE) {
    to_terminal_ = false;  // nobody reads the terminal copy any more; the logs go on
    return;
  }
  drawStatus();
}

void OutputRouter::eraseStatus() {
  if (!status_.empty()) writeAll(STDOUT_FILENO, "\r\033[K");
}

void OutputRouter::drawStatus() {
  if (!status_.empty()) writeAll(STDOUT_FILENO, status_);
}

void OutputRouter::status(const std::string& text) {
  if (!to_terminal_) return;
  eraseStatus();
  status_ = text;
  drawStatus();
}

void OutputRouter::keepStatus() {
  if (to_terminal_ && !status_.empty()) writeAll(STDOUT_FILENO, "\n");
  status_.clear();
}

}  // namespace climbsim::launcher
