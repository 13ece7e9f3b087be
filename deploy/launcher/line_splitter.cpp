#include "line_splitter.hpp"

namespace climbsim::launcher {

namespace {
std::string_view withoutCarriageReturn(std::string_view line) {
  if (!line.empty() && line.back() == '\r') {
    line.remove_suffix(1);
  }
  return line;
}
}  // namespace

void LineSplitter::feed(std::string_view bytes, const Emit& emit) {
  while (!bytes.empty()) {
    const std::size_t newline = bytes.find('\n');
    if (newline == std::string_view::npos) {
      pending_.append(bytes);
      bytes = {};
    } else {
      pending_.append(bytes.substr(0, newline));
      bytes.remove_prefix(newline + 1);
      emit(withoutCarriageReturn(pending_));
      pending_.clear();
    }
    while (pending_.size() >= max_line_) {
      emit(std::string_view(pending_).substr(0, max_line_));
      pending_.erase(0, max_line_);
    }
  }
}

void LineSplitter::finish(const Emit& emit) {
  if (!pending_.empty()) {
    emit(withoutCarriageReturn(pending_));
    pending_.clear();
  }
}

}  // namespace climbsim::launcher
