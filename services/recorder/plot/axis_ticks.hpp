#pragma once
/// @file
/// Axis ranges with "nice" ticks for the plots: steps of 1, 2 or 5 times a power of ten, the
/// range widened to whole steps around the data.

#include <string>
#include <vector>

namespace climbsim::plot {

struct AxisTicks {
  double lo = 0.0;            ///< first tick = lower end of the axis
  double hi = 1.0;            ///< last tick = upper end of the axis, > lo
  double step = 0.2;          ///< distance between ticks, {1, 2, 5} * 10^k
  std::vector<double> ticks;  ///< lo, lo + step, ..., hi
};

/// Ticks covering [data_lo, data_hi] with at most `max_intervals` (>= 1) intervals: the smallest
/// step s in {1, 2, 5} * 10^k with ceil(hi/s) - floor(lo/s) <= max_intervals, lo = floor(data_lo/s) s,
/// hi = ceil(data_hi/s) s (ends within rounding of the data are the data's own). An empty range (data_lo == data_hi) is widened by 10 % of |v| each side, [-1, 1] for 0;
/// non-finite ends give [0, 1].
AxisTicks niceTicks(double data_lo, double data_hi, int max_intervals = 6);

/// A tick label with as many decimals as `step` needs ("0.25" for step 0.05, "1200" for 200);
/// -0 is written 0.
std::string tickLabel(double value, double step);

/// Maps [v0, v1] linearly onto [p0, p1] (pixels; p1 < p0 for a y axis growing upwards).
struct LinearMap {
  double v0 = 0.0, v1 = 1.0;
  double p0 = 0.0, p1 = 1.0;
  double operator()(double v) const { return p0 + (v - v0) * (p1 - p0) / (v1 - v0); }
};

}  // namespace climbsim::plot
