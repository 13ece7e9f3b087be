#pragma once
/// @file
/// Line charts over time drawn with OpenCV: one or more panels stacked vertically, sharing the
/// x axis, each with ticks, tick labels, an axis label with units, a legend right of its plot
/// area, and a title over the whole picture. Data lines are drawn without anti-aliasing (every pixel of a curve has the
/// series' exact colour); text is anti-aliased.

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "axis_ticks.hpp"

namespace climbsim::plot {

/// One curve. Points with a non-finite x or y break the line.
struct Series {
  std::string label;
  std::vector<double> x, y;
  cv::Scalar colour;     ///< BGR
  bool dashed = false;   ///< e.g. a set-point
};

struct Panel {
  std::string y_label;  ///< with units, e.g. "F [N]"
  std::vector<Series> series;
  int height_px = 0;    ///< 0: the chart's panel_height_px
  /// The smallest y range shown [y units]: a narrower data range (a constant series) is
  /// widened to it around its middle; 0: niceTicks' own widening.
  double min_span = 0.0;
  /// y values the axis always shows (e.g. {0, 1} for valve openings), data or not.
  std::vector<double> y_include{};
};

/// A moment marked across every panel: a vertical line at x with its label at the top of the
/// first panel (e.g. "released", "FELL").
struct Marker {
  double x = 0.0;
  std::string label;
  cv::Scalar colour;  ///< BGR
};

struct ChartSpec {
  std::string title;
  std::string x_label = "t [s]";
  std::vector<Panel> panels;
  int width_px = 1200;
  int panel_height_px = 380;
  /// One y axis for all panels (small multiples of one quantity compare at a glance).
  bool shared_y = false;
  /// Moments marked in every panel (only those within the x range are drawn).
  std::vector<Marker> markers;
};

/// Total height of the chart [px]: title, panels, x label.
int chartHeight(const ChartSpec& spec);

/// Where a panel's data land: the plot rectangle (pixels) and its axes.
struct PanelLayout {
  cv::Rect plot_px;  ///< inner plot area; x.lo at its left column, x.hi at its right column
  AxisTicks x, y;    ///< y.lo at the bottom row, y.hi at the top row
};

/// Layout of every panel: x ticks over all series of all panels, y ticks per panel over its series
/// and y_include, at least min_span wide (or over all panels with shared_y). The y range is
/// padded so that no value lies on the frame.
std::vector<PanelLayout> chartLayout(const ChartSpec& spec);

/// The right edge [px] of a panel's rotated y axis label; its y tick labels end kTickGap (8 px)
/// left of the plot area and start right of this edge (the layout widens the left margin).
int yLabelRight(const Panel& panel);

/// Pixel (column, row) of the data point (x, y) in a panel, rounded to the nearest pixel.
cv::Point toPixel(const PanelLayout& layout, double x, double y);

/// The chart as an 8-bit BGR image of width_px x (panels * panel_height_px + title and x label).
cv::Mat drawChart(const ChartSpec& spec);

/// The i-th colour of the plots' palette (BGR, distinct for i = 0..9, then repeating).
cv::Scalar paletteColour(int i);

}  // namespace climbsim::plot
