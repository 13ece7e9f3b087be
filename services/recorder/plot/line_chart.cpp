#include "line_chart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

namespace climbsim::plot {
namespace {

constexpr int kTitleH = 44;   // title band
constexpr int kBottomH = 46;  // x label band under the last panel
constexpr int kLeft = 96;     // y tick labels and y axis label (at least; wider tick labels widen it)
constexpr int kYLabelX = 6;   // left edge of the rotated y axis label
constexpr int kTickGap = 8;   // between a y tick label and the plot area
constexpr int kRight = 24;     // right margin without a legend
constexpr int kLegendSample = 28, kLegendRow = 18;
constexpr int kPanelTop = 14;     // space inside a panel above its plot area
constexpr int kPanelBottom = 30;  // x tick labels inside a panel
const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225), kWhite(255, 255, 255), kGreyText(60, 60, 60);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

void rangeOf(const std::vector<double>& v, double& lo, double& hi) {
  for (double d : v) {
    if (std::isfinite(d)) {
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
}

void putText(cv::Mat& img, const std::string& text, cv::Point org, double scale, cv::Scalar colour, int thick = 1) {
  cv::putText(img, text, org, kFont, scale, colour, thick, cv::LINE_AA);
}

cv::Size textSize(const std::string& text, double scale, int thick = 1) {
  int base = 0;
  return cv::getTextSize(text, kFont, scale, thick, &base);
}

/// A line from a to b in on/off pieces of 10/6 px; `phase` carries the pattern over segments.
void dashedLine(cv::Mat& img, cv::Point2d a, cv::Point2d b, cv::Scalar colour, int thick, double& phase) {
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  double s = 0.0;
  while (s < len) {
    const double in_period = std::fmod(phase, 16.0);
    const bool on = in_period < 10.0;
    const double piece = std::min(len - s, (on ? 10.0 : 16.0) - in_period);
    if (on && len > 0.0) {
      const cv::Point2d p = a + (b - a) * (s / len), q = a + (b - a) * ((s + piece) / len);
      cv::line(img, cv::Point(cvRound(p.x), cvRound(p.y)), cv::Point(cvRound(q.x), cvRound(q.y)), colour, thick,
               cv::LINE_8);
    }
    s += piece;
    phase += piece;
  }
}

void drawSeries(cv::Mat& img, const PanelLayout& l, const Series& s) {
  const LinearMap mx{l.x.lo, l.x.hi, double(l.plot_px.x), double(l.plot_px.x + l.plot_px.width - 1)};
  const LinearMap my{l.y.lo, l.y.hi, double(l.plot_px.y + l.plot_px.height - 1), double(l.plot_px.y)};
  const std::size_t n = std::min(s.x.size(), s.y.size());
  bool have_prev = false;
  cv::Point2d prev;
  double phase = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      have_prev = false;
      continue;
    }
    const cv::Point2d p(mx(s.x[i]), my(s.y[i]));
    if (have_prev) {
      if (s.dashed) {
        dashedLine(img, prev, p, s.colour, 2, phase);
      } else {
        cv::line(img, cv::Point(cvRound(prev.x), cvRound(prev.y)), cv::Point(cvRound(p.x), cvRound(p.y)), s.colour,
                 2, cv::LINE_8);
      }
    } else if (n == 1 || i + 1 == n || !std::isfinite(s.y[i + 1])) {
      cv::circle(img, cv::Point(cvRound(p.x), cvRound(p.y)), 2, s.colour, cv::FILLED, cv::LINE_8);
    }
    prev = p;
    have_prev = true;
  }
}

/// Width of the legend box of a panel (0 without labels).
int legendWidth(const Panel& panel) {
  int text_w = -1;
  for (const auto& s : panel.series) {
    if (!s.label.empty()) text_w = std::max(text_w, textSize(s.label, 0.45).width);
  }
  return text_w < 0 ? 0 : 8 + kLegendSample + 6 + text_w + 8;
}

/// The legend right of the plot area (never over the data), top aligned with it.
void drawLegend(cv::Mat& img, const PanelLayout& l, const Panel& panel) {
  std::vector<const Series*> shown;
  for (const auto& s : panel.series) {
    if (!s.label.empty()) shown.push_back(&s);
  }
  if (shown.empty()) return;
  const int w = legendWidth(panel);
  const int h = 6 + kLegendRow * static_cast<int>(shown.size()) + 2;
  const cv::Rect box(l.plot_px.x + l.plot_px.width + 10, l.plot_px.y, w, h);
  cv::rectangle(img, box, kWhite, cv::FILLED);
  cv::rectangle(img, box, cv::Scalar(160, 160, 160), 1);
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const int y = box.y + 6 + kLegendRow * static_cast<int>(i) + kLegendRow / 2;
    double phase = 0.0;
    if (shown[i]->dashed) {
      dashedLine(img, cv::Point2d(box.x + 8, y), cv::Point2d(box.x + 8 + kLegendSample, y), shown[i]->colour, 2,
                 phase);
    } else {
      cv::line(img, cv::Point(box.x + 8, y), cv::Point(box.x + 8 + kLegendSample, y), shown[i]->colour, 2,
               cv::LINE_8);
    }
    putText(img, shown[i]->label, cv::Point(box.x + 8 + kLegendSample + 6, y + 5), 0.45, kBlack);
  }
}

}  // namespace

cv::Scalar paletteColour(int i) {
  // Tableau 10, BGR.
  static const cv::Scalar kColours[] = {
      {180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214},  {189, 103, 148},
      {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23}};
  return kColours[((i % 10) + 10) % 10];
}

namespace {
int panelHeight(const ChartSpec& spec, std::size_t i) {
  return spec.panels[i].height_px > 0 ? spec.panels[i].height_px : spec.panel_height_px;
}

/// Nice ticks of [lo, hi]; an end of the axis that the data reach is moved out by 5 % of the
/// span or 8 px of a `plot_h` px high plot, whichever is more (past the last tick), so that no
/// value lies on the frame.
AxisTicks paddedTicks(double lo, double hi, int max_intervals, int plot_h) {
  AxisTicks t = niceTicks(lo, hi, max_intervals);
  if (!std::isfinite(lo) || !std::isfinite(hi)) return t;
  const double span = t.hi - t.lo;
  const double pad = span * std::max(0.05, 8.0 / std::max(plot_h, 1));
  if (hi >= t.hi - 0.01 * span) t.hi += pad;
  if (lo <= t.lo + 0.01 * span) t.lo -= pad;
  return t;
}
}  // namespace

int chartHeight(const ChartSpec& spec) {
  int height = kTitleH + kBottomH;
  for (std::size_t i = 0; i < spec.panels.size(); ++i) height += panelHeight(spec, i);
  return height;
}

std::vector<PanelLayout> chartLayout(const ChartSpec& spec) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double all_lo = x_lo, all_hi = x_hi;
  double all_min_span = 0.0;
  for (const auto& p : spec.panels) {
    for (const auto& s : p.series) {
      rangeOf(s.x, x_lo, x_hi);
      rangeOf(s.y, all_lo, all_hi);
    }
    rangeOf(p.y_include, all_lo, all_hi);
    all_min_span = std::max(all_min_span, p.min_span);
  }
  const AxisTicks x = niceTicks(x_lo, x_hi, 10);
  int legend_w = 0;
  for (const auto& p : spec.panels) legend_w = std::max(legend_w, legendWidth(p));
  const int right = legend_w > 0 ? legend_w + 10 + 12 : kRight;
  // Shared y axes pad alike: by the smallest panel's pixels.
  int min_plot_h = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < spec.panels.size(); ++i) {
    min_plot_h = std::min(min_plot_h, panelHeight(spec, i) - kPanelTop - kPanelBottom);
  }
  std::vector<PanelLayout> out;
  int top = kTitleH;
  for (std::size_t i = 0; i < spec.panels.size(); ++i) {
    double y_lo = std::numeric_limits<double>::infinity(), y_hi = -y_lo;
    for (const auto& s : spec.panels[i].series) rangeOf(s.y, y_lo, y_hi);
    rangeOf(spec.panels[i].y_include, y_lo, y_hi);
    double min_span = spec.panels[i].min_span;
    if (spec.shared_y) {
      y_lo = all_lo;
      y_hi = all_hi;
      min_span = all_min_span;
    }
    if (std::isfinite(y_lo) && std::isfinite(y_hi) && y_hi - y_lo < min_span) {
      const double middle = 0.5 * (y_lo + y_hi);
      y_lo = middle - 0.5 * min_span;
      y_hi = middle + 0.5 * min_span;
    }
    const int height = panelHeight(spec, i);
    const int plot_h = height - kPanelTop - kPanelBottom;
    PanelLayout l;
    l.x = x;
    // About one tick label per 40 px, so that small multiples stay legible.
    const int axis_h = spec.shared_y ? min_plot_h : plot_h;
    l.y = paddedTicks(y_lo, y_hi, std::clamp(axis_h / 40, 2, 6), axis_h);
    l.plot_px = cv::Rect(kLeft, top + kPanelTop, spec.width_px - kLeft - right, plot_h);
    out.push_back(l);
    top += height;
  }
  // The left margin holds the rotated y label and the widest y tick label ("-0.00002") side by
  // side: a label that does not fit would run under the y label, which hid minus signs.
  int left = kLeft;
  for (std::size_t i = 0; i < out.size(); ++i) {
    int widest = 0;
    for (double yt : out[i].y.ticks) widest = std::max(widest, textSize(tickLabel(yt, out[i].y.step), 0.45).width);
    left = std::max(left, yLabelRight(spec.panels[i]) + 4 + widest + kTickGap);
  }
  for (auto& l : out) {
    l.plot_px.x = left;
    l.plot_px.width = std::max(1, spec.width_px - left - right);
  }
  return out;
}

int yLabelRight(const Panel& panel) { return kYLabelX + textSize(panel.y_label, 0.55).height + 10; }

cv::Point toPixel(const PanelLayout& l, double x, double y) {
  const LinearMap mx{l.x.lo, l.x.hi, double(l.plot_px.x), double(l.plot_px.x + l.plot_px.width - 1)};
  const LinearMap my{l.y.lo, l.y.hi, double(l.plot_px.y + l.plot_px.height - 1), double(l.plot_px.y)};
  return {cvRound(mx(x)), cvRound(my(y))};
}

cv::Mat drawChart(const ChartSpec& spec) {
  const int height = chartHeight(spec);
  cv::Mat img(height, spec.width_px, CV_8UC3, kWhite);
  const auto layouts = chartLayout(spec);
  const cv::Size title = textSize(spec.title, 0.8, 2);
  putText(img, spec.title, cv::Point((spec.width_px - title.width) / 2, 30), 0.8, kBlack, 2);
  for (std::size_t i = 0; i < layouts.size(); ++i) {
    const PanelLayout& l = layouts[i];
    const cv::Rect& r = l.plot_px;
    const int bottom = r.y + r.height - 1, right = r.x + r.width - 1;
    for (double xt : l.x.ticks) {
      const int px = toPixel(l, xt, l.y.lo).x;
      cv::line(img, cv::Point(px, r.y), cv::Point(px, bottom), kGrid, 1);
      cv::line(img, cv::Point(px, bottom), cv::Point(px, bottom + 5), kBlack, 1);
      const std::string label = tickLabel(xt, l.x.step);
      putText(img, label, cv::Point(px - textSize(label, 0.45).width / 2, bottom + 20), 0.45, kGreyText);
    }
    for (double yt : l.y.ticks) {
      const int py = toPixel(l, l.x.lo, yt).y;
      cv::line(img, cv::Point(r.x, py), cv::Point(right, py), kGrid, 1);
      cv::line(img, cv::Point(r.x - 5, py), cv::Point(r.x, py), kBlack, 1);
      const std::string label = tickLabel(yt, l.y.step);
      putText(img, label, cv::Point(r.x - kTickGap - textSize(label, 0.45).width, py + 5), 0.45, kGreyText);
    }
    for (const auto& s : spec.panels[i].series) drawSeries(img, l, s);
    for (std::size_t j = 0; j < spec.markers.size(); ++j) {
      const auto& m = spec.markers[j];
      if (!(m.x >= l.x.lo && m.x <= l.x.hi)) continue;
      const int px = toPixel(l, m.x, l.y.lo).x;
      cv::line(img, cv::Point(px, r.y), cv::Point(px, bottom), m.colour, 2);
      if (i == 0) {  // the label once, in the first panel, right of the line; one row each
        const int row = r.y + 16 + 18 * static_cast<int>(j);
        putText(img, m.label, cv::Point(std::min(px + 4, right - textSize(m.label, 0.5).width), row), 0.5, m.colour);
      }
    }
    cv::rectangle(img, cv::Point(r.x - 1, r.y - 1), cv::Point(right + 1, bottom + 1), kBlack, 1);
    // y label, vertical: drawn horizontally into a strip, then rotated.
    const std::string& yl = spec.panels[i].y_label;
    const cv::Size ys = textSize(yl, 0.55);
    cv::Mat strip(ys.height + 10, ys.width + 8, CV_8UC3, kWhite);
    putText(strip, yl, cv::Point(4, ys.height + 3), 0.55, kBlack);
    cv::Mat rotated;
    cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int ry = std::max(0, r.y + r.height / 2 - rotated.rows / 2);
    const int rh = std::min(rotated.rows, img.rows - ry);
    if (rh > 0 && kYLabelX + rotated.cols <= r.x) {
      rotated(cv::Rect(0, 0, rotated.cols, rh)).copyTo(img(cv::Rect(kYLabelX, ry, rotated.cols, rh)));
    }
    drawLegend(img, l, spec.panels[i]);
  }
  const cv::Size xs = textSize(spec.x_label, 0.55);
  const cv::Rect& area = layouts.empty() ? cv::Rect(kLeft, 0, spec.width_px - kLeft - kRight, 0) : layouts[0].plot_px;
  putText(img, spec.x_label, cv::Point(area.x + (area.width - xs.width) / 2, height - 16), 0.55, kBlack);
  return img;
}

}  // namespace climbsim::plot
