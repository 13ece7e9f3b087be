#include "ring_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "axis_ticks.hpp"

namespace climbsim::plot {
namespace {

constexpr int kBarW = 170;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0), kWhite(255, 255, 255), kRed(30, 30, 220);
const cv::Vec3b kUnknown(230, 230, 230);  // a chamber without a pressure value (not on the scale)

void putText(cv::Mat& img, const std::string& text, cv::Point org, double scale, cv::Scalar colour, int thick = 1) {
  cv::putText(img, text, org, kFont, scale, colour, thick, cv::LINE_AA);
}

/// Text centred on `c`, in white with a dark outline, readable on every colour.
void putCentred(cv::Mat& img, const std::string& text, cv::Point2d c, double scale) {
  int base = 0;
  const cv::Size s = cv::getTextSize(text, kFont, scale, 1, &base);
  const cv::Point org(cvRound(c.x - s.width / 2.0), cvRound(c.y + s.height / 2.0));
  putText(img, text, org, scale, kBlack, 3);
  putText(img, text, org, scale, kWhite, 1);
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

cv::Vec3b pressureColour(double p_pa, const RingScales& scales) {
  double u = (p_pa - scales.p_lo_pa) / (scales.p_hi_pa - scales.p_lo_pa);
  if (!std::isfinite(u)) u = 0.0;
  u = std::clamp(u, 0.0, 1.0);
  // OpenCV's viridis for the 256 grey levels, once: applyColorMap builds its table at every call.
  static const cv::Mat kViridis = [] {
    cv::Mat grey(1, 256, CV_8UC1);
    for (int level = 0; level < 256; ++level) grey.at<std::uint8_t>(0, level) = static_cast<std::uint8_t>(level);
    cv::Mat colour;
    cv::applyColorMap(grey, colour, cv::COLORMAP_VIRIDIS);
    return colour;
  }();
  return kViridis.at<cv::Vec3b>(0, cvRound(255.0 * u));
}

RingLayout ringLayout(const RobotGeometry&, double body_diameter_m, int size_px) {
  RingLayout l;
  l.size_px = size_px;
  l.px_per_m = 0.80 * size_px / std::max(body_diameter_m, 1e-3);
  l.centre_px = cv::Point2d(size_px / 2.0, size_px / 2.0 + 10.0);
  return l;
}

cv::Point2d ringPixel(const RingLayout& l, double yaw_rad, const RobotGeometry::Point& p) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const double x = c * p.x_m - s * p.y_m, y = s * p.x_m + c * p.y_m;
  return {l.centre_px.x + l.px_per_m * x, l.centre_px.y - l.px_per_m * y};
}

cv::Mat drawRingPicture(const RobotGeometry& g, double body_diameter_m, const RingMoment& m, const RingScales& scales,
                        int size_px) {
  const RingLayout l = ringLayout(g, body_diameter_m, size_px);
  cv::Mat img(size_px, size_px + kBarW, CV_8UC3, kWhite);
  const int sub = 4, shift_scale = 1 << sub;  // sub-pixel polygons
  auto fixed = [&](const cv::Point2d& p) { return cv::Point(cvRound(p.x * shift_scale), cvRound(p.y * shift_scale)); };

  // Body edge.
  cv::circle(img, fixed(l.centre_px), cvRound(l.px_per_m * body_diameter_m / 2.0 * shift_scale),
             cv::Scalar(200, 200, 200), cv::FILLED, cv::LINE_AA, sub);
  // Chambers, filled by pressure, black borders = the sealing strips' centre lines.
  for (std::size_t i = 0; i < g.chambers.size(); ++i) {
    std::vector<cv::Point> poly;
    for (const auto& p : g.chambers[i].outline_Robot) poly.push_back(fixed(ringPixel(l, m.yaw_rad, p)));
    const double p_pa = i < m.chamber_pa.size() ? m.chamber_pa[i] : std::nan("");
    const cv::Vec3b c = std::isfinite(p_pa) ? pressureColour(p_pa, scales) : kUnknown;
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(c[0], c[1], c[2]), cv::LINE_8, sub);
    cv::polylines(img, std::vector<std::vector<cv::Point>>{poly}, true, kBlack, 2, cv::LINE_AA, sub);
  }
  // Labels: ring chambers on the bisector just outside the inner strip (the wheels sit further
  // out), the centre chamber above its middle (P_F is usually near the middle).
  for (std::size_t i = 0; i < g.chambers.size(); ++i) {
    const auto& ch = g.chambers[i];
    cv::Point2d at_px;
    if (ch.span_rad < 6.0) {
      const double r = ch.inner_radius_m + 0.2 * (ch.outer_radius_m - ch.inner_radius_m);
      at_px = ringPixel(l, m.yaw_rad, {r * std::cos(ch.centre_angle_rad), r * std::sin(ch.centre_angle_rad)});
    } else {
      at_px = l.centre_px + cv::Point2d(0.0, -0.6 * ch.outer_radius_m * l.px_per_m);
    }
    const double p_pa = i < m.chamber_pa.size() ? m.chamber_pa[i] : std::nan("");
    putCentred(img, std::to_string(ch.number), at_px + cv::Point2d(0, -9), 0.55);
    putCentred(img, std::isfinite(p_pa) ? fmt("%.1f kPa", p_pa / 1e3) : "no value", at_px + cv::Point2d(0, 11), 0.42);
  }
  // Robot x axis (from the centre).
  const cv::Point2d o = ringPixel(l, m.yaw_rad, {0.0, 0.0});
  const cv::Point2d ax = ringPixel(l, m.yaw_rad, {0.06, 0.0});
  cv::arrowedLine(img, o, ax, kWhite, 2, cv::LINE_AA, 0, 0.25);
  // Wheels: circle area proportional to the load.
  const double r_max_px = 0.045 * l.px_per_m;
  for (std::size_t w = 0; w < g.wheels.size(); ++w) {
    const cv::Point2d c = ringPixel(l, m.yaw_rad, g.wheels[w].p_RobotWheel);
    const double load = w < m.wheel_normal_n.size() ? m.wheel_normal_n[w] : std::nan("");
    const double frac = std::isfinite(load) ? std::max(0.0, load) / scales.load_max_n : 0.0;
    const double r_px = r_max_px * std::sqrt(std::min(frac, 4.0));
    if (r_px >= 1.0) {
      cv::circle(img, fixed(c), cvRound(r_px * shift_scale), cv::Scalar(40, 40, 40), cv::FILLED, cv::LINE_AA, sub);
      cv::circle(img, fixed(c), cvRound(r_px * shift_scale), kWhite, 2, cv::LINE_AA, sub);
    } else {
      cv::drawMarker(img, c, kWhite, cv::MARKER_TILTED_CROSS, 12, 2, cv::LINE_AA);
    }
    // The load's value radially outside the largest circle.
    const auto& wp = g.wheels[w].p_RobotWheel;
    const double rw = std::hypot(wp.x_m, wp.y_m), out_m = rw + 0.045 + 0.018;
    const RobotGeometry::Point label = rw > 0.0 ? RobotGeometry::Point{wp.x_m * out_m / rw, wp.y_m * out_m / rw}
                                                : RobotGeometry::Point{0.0, -out_m};
    putCentred(img, fmt("%.0f N", load), ringPixel(l, m.yaw_rad, label), 0.45);
  }
  // P_F.
  const cv::Point2d pf = ringPixel(l, m.yaw_rad, {m.pf_x_m, m.pf_y_m});
  cv::drawMarker(img, o, kBlack, cv::MARKER_CROSS, 14, 1, cv::LINE_AA);
  cv::circle(img, fixed(pf), 7 * shift_scale, kRed, 3, cv::LINE_AA, sub);
  cv::drawMarker(img, pf, kRed, cv::MARKER_CROSS, 22, 2, cv::LINE_AA);

  // Caption.
  putText(img, fmt("t = %.3f s", m.t_s), cv::Point(12, 26), 0.65, kBlack, 2);
  // P_F in mm with one decimal; what rounds to zero is written without a sign.
  auto mm = [](double v_m) { return std::abs(v_m) < 0.05e-3 ? 0.0 : v_m * 1e3; };
  putText(img, fmt("F = %.0f N", m.downforce_n) + fmt("   P_F = (%.1f, ", mm(m.pf_x_m)) +
                   fmt("%.1f) mm in R", mm(m.pf_y_m)),
          cv::Point(12, 50), 0.5, kBlack);
  if (std::isfinite(m.reservoir_pa)) putText(img, fmt("p_R = %.1f kPa", m.reservoir_pa / 1e3), cv::Point(12, 72), 0.5, kBlack);
  putText(img, "up = up the wall; white arrow = robot x", cv::Point(12, size_px - 36), 0.45, kBlack);
  putText(img, "red = P_F; wheel circle area ~ normal load", cv::Point(12, size_px - 14), 0.45, kBlack);

  // Colour bar: p_lo at the bottom, p_hi at the top.
  const int bx = size_px + 24, by = 60, bw = 28, bh = size_px - 130;
  for (int row = 0; row < bh; ++row) {
    const double p = scales.p_hi_pa - (scales.p_hi_pa - scales.p_lo_pa) * row / (bh - 1.0);
    const cv::Vec3b c = pressureColour(p, scales);
    cv::line(img, cv::Point(bx, by + row), cv::Point(bx + bw - 1, by + row), cv::Scalar(c[0], c[1], c[2]), 1);
  }
  cv::rectangle(img, cv::Rect(bx - 1, by - 1, bw + 2, bh + 2), kBlack, 1);
  const AxisTicks t = niceTicks(scales.p_lo_pa / 1e3, scales.p_hi_pa / 1e3, 8);
  for (double v : t.ticks) {
    if (v < scales.p_lo_pa / 1e3 - 1e-9 || v > scales.p_hi_pa / 1e3 + 1e-9) continue;
    const int y = by + cvRound((scales.p_hi_pa - v * 1e3) / (scales.p_hi_pa - scales.p_lo_pa) * (bh - 1));
    cv::line(img, cv::Point(bx + bw, y), cv::Point(bx + bw + 5, y), kBlack, 1);
    putText(img, tickLabel(v, t.step), cv::Point(bx + bw + 9, y + 5), 0.45, kBlack);
  }
  putText(img, "p [kPa]", cv::Point(bx - 8, by - 16), 0.55, kBlack);
  putText(img, "wheels: largest", cv::Point(size_px + 8, by + bh + 34), 0.42, kBlack);
  putText(img, fmt("circle = %.0f N", scales.load_max_n), cv::Point(size_px + 8, by + bh + 54), 0.42, kBlack);
  return img;
}

}  // namespace climbsim::plot
