#include "axis_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace climbsim::plot {

AxisTicks niceTicks(double data_lo, double data_hi, int max_intervals) {
  max_intervals = std::max(1, max_intervals);
  if (!std::isfinite(data_lo) || !std::isfinite(data_hi)) {
    data_lo = 0.0;
    data_hi = 1.0;
  }
  if (data_lo > data_hi) std::swap(data_lo, data_hi);
  if (data_hi - data_lo <= 1e-12 * std::max(std::abs(data_lo), std::abs(data_hi))) {
    // A constant: 10 % of it each side, and a unit each side of 0 (not +-1e-9: tick labels
    // of "0.000000001" say nothing).
    const double pad = data_lo == 0.0 ? 1.0 : 0.1 * std::abs(data_lo);
    data_lo -= pad;
    data_hi += pad;
  }
  const double raw = (data_hi - data_lo) / max_intervals;
  double step = std::pow(10.0, std::floor(std::log10(raw)));
  AxisTicks t;
  // At most a few rounds: 1, 2, 5, 10, ... times the power of ten below raw.
  for (int k = 0; k < 12; ++k) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double s = m * step;
      // The 1e-9 (relative) keeps data on a tick (10 / 0.1 = 100.00000000000001) from adding an interval;
      // what rounding then leaves outside by a few ulps is taken into the end ticks.
      const double qlo = data_lo / s, qhi = data_hi / s;
      double lo = std::floor(qlo + std::max(1e-9, 1e-12 * std::abs(qlo)));
      double hi = std::ceil(qhi - std::max(1e-9, 1e-12 * std::abs(qhi)));
      if (lo * s > data_lo + 1e-9 * s) lo -= 1.0;
      if (hi * s < data_hi - 1e-9 * s) hi += 1.0;
      if (hi - lo <= max_intervals) {
        t.step = s;
        t.lo = std::min(lo * s, data_lo);
        t.hi = std::max(hi * s, data_hi);
        for (double i = lo; i <= hi + 0.5; i += 1.0) t.ticks.push_back(i * s == 0.0 ? 0.0 : i * s);
        return t;
      }
    }
    step *= 10.0;
  }
  t.lo = data_lo;
  t.hi = data_hi;
  t.step = data_hi - data_lo;
  t.ticks = {data_lo, data_hi};
  return t;
}

std::string tickLabel(double value, double step) {
  int decimals = 0;
  if (step > 0.0 && std::isfinite(step)) {
    decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    // 0.25 steps need two decimals: add one while the step is not whole at that precision.
    const double scaled = step * std::pow(10.0, decimals);
    if (std::abs(scaled - std::round(scaled)) > 1e-6) ++decimals;
  }
  if (std::abs(value) < 1e-12 * std::max(1.0, step)) value = 0.0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 12), value);
  std::string s = buf;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s = s.substr(1);
  return s;
}

}  // namespace climbsim::plot
