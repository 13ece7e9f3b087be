#include "climbsim/errors.hpp"

#include <algorithm>

namespace climbsim {

void ErrorList::add(int line, const std::string& message) {
  for (const auto& p : problems_) {
    if (p.message == message) return;  // one missing section is one problem, not one per key
  }
  problems_.push_back(Problem{line, message});
}

void ErrorList::throwIfAny() const {
  if (problems_.empty()) return;
  std::vector<Problem> sorted = problems_;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Problem& a, const Problem& b) { return a.line < b.line; });
  std::string text;
  const std::size_t shown = std::min(sorted.size(), kMaxReported);
  for (std::size_t i = 0; i < shown; ++i) {
    text += (i == 0 ? "" : "\n") + sorted[i].message;
  }
  if (sorted.size() > shown) {
    text += "\n... and " + std::to_string(sorted.size() - shown) + " more problems";
  }
  throw ConfigError(text);
}

}  // namespace climbsim
