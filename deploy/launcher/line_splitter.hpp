#pragma once
/// @file
/// Cuts a byte stream (a child's output pipe) into lines.

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace climbsim::launcher {

/// Accumulates chunks and hands out complete lines, without the '\n' (and without a '\r'
/// before it). A line longer than `max_line` bytes is handed out in pieces of that size,
/// so a child that never ends a line cannot make the buffer grow without bound.
class LineSplitter {
 public:
  using Emit = std::function<void(std::string_view line)>;

  explicit LineSplitter(std::size_t max_line = 64 * 1024) : max_line_(max_line) {}

  /// Appends `bytes` and emits every line they complete.
  void feed(std::string_view bytes, const Emit& emit);

  /// Emits what is left after the last '\n' (the stream ended), if anything.
  void finish(const Emit& emit);

 private:
  std::size_t max_line_;
  std::string pending_;
};

}  // namespace climbsim::launcher
