#include "figure9_plot.hpp"

#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "line_chart.hpp"

namespace climbsim::plot {
namespace {

Series level(const std::vector<double>& x, double value, const std::string& label, cv::Scalar colour) {
  Series s{label, {}, {}, colour, true};
  double lo = INFINITY, hi = -INFINITY;
  for (double v : x) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (lo <= hi) {
    s.x = {lo, hi};
    s.y = {value, value};
  }
  return s;
}

}  // namespace

std::vector<double> crackOffsetAlongX(const TraceTable& trace, double crack_y_m) {
  const auto& y = trace.column("y_m");
  const auto& yaw = trace.column("yaw_rad");
  std::vector<double> out(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double s = std::sin(yaw[k]);
    out[k] = std::abs(s) < 0.5 ? std::numeric_limits<double>::quiet_NaN() : (crack_y_m - y[k]) / s;
  }
  return out;
}

cv::Mat figure9Plot(const TraceTable& trace, double crack_y_m, double from_s, const Figure9Reference& reference) {
  std::vector<double> x = crackOffsetAlongX(trace, crack_y_m);
  const auto& t = trace.column("t_s");
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (t[k] < from_s) x[k] = std::numeric_limits<double>::quiet_NaN();
  }
  const auto& pf_x = trace.column("pf_x_m");
  const auto& pf_y = trace.column("pf_y_m");
  std::vector<double> pf_mm(pf_x.size());
  for (std::size_t k = 0; k < pf_x.size(); ++k) pf_mm[k] = 1e3 * std::hypot(pf_x[k], pf_y[k]);
  const std::string x_label = "crack along R's x from the centre [m] (+ ahead/below .. - behind/above)";

  ChartSpec force;
  force.title = "Downforce F across the crack: climbsim vs the original's figure 9";
  force.x_label = x_label;
  force.width_px = 900;
  force.panels = {Panel{"F [N]",
                        {Series{"F (climbsim)", x, trace.column("downforce_n"), paletteColour(0), false},
                         level(x, reference.downforce_before_n, "original: before the crack", paletteColour(3)),
                         level(x, reference.downforce_on_crack_n, "original: on the crack", paletteColour(1))}}};
  ChartSpec pf;
  pf.title = "Offset of the point of action |P_F|";
  pf.x_label = x_label;
  pf.width_px = 900;
  pf.panels = {Panel{"|P_F| [mm]",
                     {Series{"|P_F| (climbsim)", x, pf_mm, paletteColour(2), false},
                      level(x, 1e3 * reference.pf_offset_m, "original: about 80 mm", paletteColour(1))}}};
  const cv::Mat left = drawChart(force);
  const cv::Mat right = drawChart(pf);
  cv::Mat both;
  cv::hconcat(left, right, both);
  return both;
}

}  // namespace climbsim::plot
