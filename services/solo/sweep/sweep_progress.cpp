#include "sweep_progress.hpp"

#include <cstdio>

namespace climbsim::sweep {

std::string progressLine(const SweepCounts& c, double elapsed_s) {
  constexpr std::size_t kWidth = 30;
  const std::size_t filled = c.total > 0 ? kWidth * c.done / c.total : kWidth;
  char left[64] = "";
  if (c.done > 0 && c.done < c.total) {
    std::snprintf(left, sizeof(left), ", about %.0f s left",
                  elapsed_s / static_cast<double>(c.done) * static_cast<double>(c.total - c.done));
  }
  char text[256];
  std::snprintf(text, sizeof(text), "sweep: [%s%s] %zu/%zu done (%zu fell, %zu slid, %zu failed), %zu running, "
                "%zu queued, %.0f s%s",
                std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(), c.done, c.total, c.fell,
                c.slid, c.failed, c.running, c.queued, elapsed_s, left);
  return text;
}

}  // namespace climbsim::sweep
