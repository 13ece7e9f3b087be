#pragma once
/// @file
/// Where the output lines of supervised processes go: the terminal, prefixed with the
/// process name like docker compose does, and each process's log files, unprefixed.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace climbsim::launcher {

/// True if standard output is a terminal and NO_COLOR is not set.
bool terminalWantsColor();

/// "name  | " padded to `width` characters, colored by `index` if `color`.
std::string linePrefix(const std::string& name, std::size_t width, std::size_t index, bool color);

/// Copies lines to the terminal and to log files.
class OutputRouter {
 public:
  /// `names` are the processes in order; `to_terminal` sends prefixed lines to stdout.
  OutputRouter(const std::vector<std::string>& names, bool to_terminal, bool color);
  ~OutputRouter();
  OutputRouter(const OutputRouter&) = delete;
  OutputRouter& operator=(const OutputRouter&) = delete;

  /// Appends every line of process `index` also to `path` (created, truncated first).
  /// Throws std::runtime_error if it cannot be opened.
  void addLogFile(std::size_t index, const std::string& path);

  /// One line (without its '\n') of process `index`.
  void line(std::size_t index, std::string_view text);

  /// Shows `text` as the live status line below the output (a terminal only: rewritten in
  /// place with '\r'; the lines of the processes scroll above it). Empty hides it.
  void status(const std::string& text);

  /// Leaves the status line on the terminal as an ordinary line (the run's last word).
  void keepStatus();

 private:
  struct Target {
    std::string prefix;
    std::vector<int> log_fds;
  };
  void eraseStatus();
  void drawStatus();

  std::vector<Target> targets_;
  bool to_terminal_;
  std::string status_;
};

}  // namespace climbsim::launcher
