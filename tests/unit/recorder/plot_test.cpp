// The plot library without DDS: axis ticks, where a curve lands, ring picture colours, the
// trace reader's one-line errors, and the sealing picture file assignment.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "node/sealing_picture_files.hpp"
#include "plot/axis_ticks.hpp"
#include "plot/line_chart.hpp"
#include "plot/picture_names.hpp"
#include "plot/ring_picture.hpp"
#include "plot/run_plots.hpp"
#include "plot/sealing_picture.hpp"
#include "plot/trace_table.hpp"

namespace climbsim::plot {
namespace {

bool isNiceStep(double step) {
  const double e = std::floor(std::log10(step) + 1e-9);
  const double m = step / std::pow(10.0, e);
  return std::abs(m - 1.0) < 1e-9 || std::abs(m - 2.0) < 1e-9 || std::abs(m - 5.0) < 1e-9;
}

TEST(AxisTicks, KnownRanges) {
  const AxisTicks a = niceTicks(0.0, 9.7, 6);
  EXPECT_DOUBLE_EQ(a.lo, 0.0);
  EXPECT_DOUBLE_EQ(a.hi, 10.0);
  EXPECT_DOUBLE_EQ(a.step, 2.0);
  ASSERT_EQ(a.ticks.size(), 6u);
  EXPECT_DOUBLE_EQ(a.ticks[3], 6.0);

  const AxisTicks p = niceTicks(96100.0, 101325.0, 6);  // chamber pressures [Pa]
  EXPECT_DOUBLE_EQ(p.step, 1000.0);
  EXPECT_DOUBLE_EQ(p.lo, 96000.0);
  EXPECT_DOUBLE_EQ(p.hi, 102000.0);

  const AxisTicks n = niceTicks(-0.013, 0.021, 6);  // P_F [m]
  EXPECT_NEAR(n.step, 0.01, 1e-15);
  EXPECT_NEAR(n.lo, -0.02, 1e-15);
  EXPECT_NEAR(n.hi, 0.03, 1e-15);
}

TEST(AxisTicks, CoverTheDataWithFewNiceSteps) {
  for (double lo : {-1234.5, -3.0, 0.0, 0.001, 17.0}) {
    for (double span : {1e-6, 0.37, 1.0, 42.0, 9e5}) {
      for (int max_intervals : {2, 5, 6, 10}) {
        const AxisTicks t = niceTicks(lo, lo + span, max_intervals);
        EXPECT_LE(t.lo, lo);
        EXPECT_GE(t.hi, lo + span);
        EXPECT_TRUE(isNiceStep(t.step)) << t.step;
        EXPECT_LE(static_cast<int>(t.ticks.size()) - 1, max_intervals);
        EXPECT_NEAR((t.hi - t.lo) / t.step, static_cast<double>(t.ticks.size() - 1), 1e-3);
        // The next smaller nice step would need more intervals: the step is the smallest
        // (checked where the data are not a tiny span far from zero, i.e. well conditioned).
        if (std::abs(lo) > 1e4 * span) continue;
        const double m = t.step / std::pow(10.0, std::floor(std::log10(t.step) + 1e-9));
        const double smaller = t.step * (m < 1.5 ? 0.5 : m < 3.0 ? 0.5 : 0.4);
        EXPECT_GT(std::ceil((lo + span) / smaller - 1e-9) - std::floor(lo / smaller + 1e-9), max_intervals)
            << lo << " + " << span << " step " << t.step;
      }
    }
  }
}

TEST(AxisTicks, ConstantAndNonFiniteData) {
  const AxisTicks c = niceTicks(5.0, 5.0, 6);
  EXPECT_LT(c.lo, 5.0);
  EXPECT_GT(c.hi, 5.0);
  const AxisTicks z = niceTicks(0.0, 0.0, 6);
  EXPECT_LT(z.lo, 0.0);
  EXPECT_GT(z.hi, 0.0);
  EXPECT_GE(z.step, 0.2) << "a unit each side of 0, not 1e-9";
  EXPECT_LE(z.hi, 1.0);
  const AxisTicks nf = niceTicks(NAN, INFINITY, 6);
  EXPECT_DOUBLE_EQ(nf.lo, 0.0);
  EXPECT_DOUBLE_EQ(nf.hi, 1.0);
}

TEST(AxisTicks, LabelsHaveTheDecimalsOfTheStep) {
  EXPECT_EQ(tickLabel(0.25, 0.05), "0.25");
  EXPECT_EQ(tickLabel(1200.0, 200.0), "1200");
  EXPECT_EQ(tickLabel(0.5, 0.25), "0.50");
  EXPECT_EQ(tickLabel(-1e-17, 0.1), "0.0");
  EXPECT_EQ(tickLabel(-0.3, 0.1), "-0.3");
}

TEST(LineChart, NegativeTickLabelsNearZeroKeepTheirMinusSignLeftOfTheYLabel) {
  // P_F of a run whose force is still building: a few hundredths of a millimetre about zero.
  // The y tick labels ("-0.00002") must not run under the rotated y label, which would hide
  // the minus.
  ChartSpec spec;
  spec.title = "P_F";
  Series s{"P_F x", {0.0, 1.0, 2.0, 3.0}, {-2.2e-5, 1.3e-5, -0.4e-5, 2.1e-5}, paletteColour(0), false};
  spec.panels = {Panel{"P_F x [m]", {s}}, Panel{"F [N]", {Series{"F", {0.0, 3.0}, {0.0, 2200.0}, paletteColour(1), false}}}};
  const auto layouts = chartLayout(spec);
  ASSERT_EQ(layouts.size(), 2u);
  EXPECT_EQ(layouts[0].plot_px.x, layouts[1].plot_px.x) << "the panels share the x axis";
  int negative = 0;
  for (std::size_t i = 0; i < layouts.size(); ++i) {
    const auto& l = layouts[i];
    for (double yt : l.y.ticks) {
      const std::string label = tickLabel(yt, l.y.step);
      if (yt < 0.0) {
        ++negative;
        EXPECT_EQ(label.front(), '-') << label;
      }
      int base = 0;
      const int width = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &base).width;
      EXPECT_GE(l.plot_px.x - 8 - width, yLabelRight(spec.panels[i])) << label << " runs under the y label";
    }
  }
  EXPECT_GT(negative, 0) << "the test needs ticks below zero";
  // A narrow label keeps the usual margin.
  ChartSpec plain;
  plain.panels = {Panel{"F [N]", {Series{"F", {0.0, 3.0}, {0.0, 2200.0}, paletteColour(1), false}}}};
  EXPECT_EQ(chartLayout(plain)[0].plot_px.x, 96);
  const cv::Mat img = drawChart(spec);
  EXPECT_EQ(img.cols, spec.width_px);
}

TEST(LineChart, ACurveOfKnownValuesLandsOnItsPixels) {
  ChartSpec spec;
  spec.title = "test";
  Series s{"y = x", {}, {}, paletteColour(2), false};
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i * 0.1);
    s.y.push_back(i * 0.1);
  }
  spec.panels = {Panel{"y [1]", {s}}};
  const auto layouts = chartLayout(spec);
  ASSERT_EQ(layouts.size(), 1u);
  const PanelLayout& l = layouts[0];
  // x from 0 to 10 (ticks of 1); y ticks 0 to 10 (of 2) with a margin of 5 % beyond the data's
  // ends, so that no value lies on the frame.
  EXPECT_DOUBLE_EQ(l.x.lo, 0.0);
  EXPECT_DOUBLE_EQ(l.x.hi, 10.0);
  EXPECT_DOUBLE_EQ(l.y.step, 2.0);
  EXPECT_DOUBLE_EQ(l.y.lo, -0.5);
  EXPECT_DOUBLE_EQ(l.y.hi, 10.5);
  EXPECT_DOUBLE_EQ(l.y.ticks.front(), 0.0);
  EXPECT_DOUBLE_EQ(l.y.ticks.back(), 10.0);
  EXPECT_EQ(toPixel(l, 0.0, -0.5), cv::Point(l.plot_px.x, l.plot_px.y + l.plot_px.height - 1));
  EXPECT_EQ(toPixel(l, 10.0, 10.5), cv::Point(l.plot_px.x + l.plot_px.width - 1, l.plot_px.y));
  EXPECT_LT(toPixel(l, 0.0, 0.0).y, l.plot_px.y + l.plot_px.height - 10);
  EXPECT_GT(toPixel(l, 10.0, 10.0).y, l.plot_px.y + 10);
  const cv::Point mid = toPixel(l, 5.0, 5.0);
  EXPECT_NEAR(mid.x, l.plot_px.x + (l.plot_px.width - 1) / 2.0, 0.5);
  EXPECT_NEAR(mid.y, l.plot_px.y + (l.plot_px.height - 1) / 2.0, 0.5);

  const cv::Mat img = drawChart(spec);
  EXPECT_EQ(img.cols, spec.width_px);
  EXPECT_EQ(img.type(), CV_8UC3);
  const cv::Scalar c = paletteColour(2);
  const cv::Vec3b colour(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
  for (double v : {0.5, 1.0, 2.3, 4.0, 5.0, 6.7, 9.2, 9.9}) {  // the legend is outside the plot area
    const cv::Point p = toPixel(l, v, v);
    EXPECT_EQ(img.at<cv::Vec3b>(p), colour) << "at " << v;
  }
  // Far from the curve: not its colour.
  EXPECT_NE(img.at<cv::Vec3b>(toPixel(l, 2.0, 8.0)), colour);
  EXPECT_NE(img.at<cv::Vec3b>(toPixel(l, 8.0, 2.0)), colour);
}

TEST(LineChart, MarkersCrossEveryPanelAtTheirTimeOnly) {
  ChartSpec spec;
  Series s{"", {0.0, 10.0}, {0.0, 1.0}, paletteColour(0), false};
  spec.panels = {Panel{"a", {s}, 150}, Panel{"b", {s}, 150}};
  const cv::Scalar red(0, 0, 220), blue(160, 100, 0);
  spec.markers = {{7.6, "FELL", red}, {2.0, "released", blue}, {25.0, "beyond the trace", cv::Scalar(0, 200, 0)}};
  const cv::Mat img = drawChart(spec);
  const auto layouts = chartLayout(spec);
  const cv::Vec3b r(0, 0, 220), b(160, 100, 0), g(0, 200, 0);
  for (const auto& l : layouts) {
    const int mid_row = l.plot_px.y + l.plot_px.height / 2;
    EXPECT_EQ(img.at<cv::Vec3b>(mid_row, toPixel(l, 7.6, 0.0).x), r);
    EXPECT_EQ(img.at<cv::Vec3b>(mid_row, toPixel(l, 2.0, 0.0).x), b);
    EXPECT_NE(img.at<cv::Vec3b>(mid_row, toPixel(l, 5.0, 0.0).x), r);
  }
  // A marker outside the x range is not drawn anywhere.
  bool any_green = false;
  for (int y = 0; y < img.rows && !any_green; ++y)
    for (int x = 0; x < img.cols && !any_green; ++x) any_green = img.at<cv::Vec3b>(y, x) == g;
  EXPECT_FALSE(any_green);
}

TEST(RunPlots, ReleaseAndFallAreMarkedFromTheScenarioAndTheSummary) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "climbsim-plot-markers-test";
  std::filesystem::create_directories(dir);
  Scenario scenario;
  scenario.start.hold_s = 2.0;
  std::ofstream(dir / "summary.json", std::ios::trunc) << R"({"fell": true, "fell_at_s": 7.6})";
  auto marks = runMarkers(scenario, dir.string());
  ASSERT_EQ(marks.size(), 2u);
  EXPECT_EQ(marks[0].label, "released");
  EXPECT_DOUBLE_EQ(marks[0].x, 2.0);
  EXPECT_EQ(marks[1].label, "FELL");
  EXPECT_DOUBLE_EQ(marks[1].x, 7.6);
  // No hold, no fall (null), no summary at all: nothing marked.
  scenario.start.hold_s = 0.0;
  std::ofstream(dir / "summary.json", std::ios::trunc) << R"({"fell": false, "fell_at_s": null})";
  EXPECT_TRUE(runMarkers(scenario, dir.string()).empty());
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(runMarkers(scenario, dir.string()).empty());
}

TEST(LineChart, NonFiniteValuesBreakTheLine) {
  ChartSpec spec;
  Series s{"", {0.0, 1.0, 2.0, 3.0, 4.0}, {0.0, 0.0, NAN, 0.0, 0.0}, paletteColour(0), false};
  Series t{"", {0.0, 4.0}, {-1.0, 1.0}, paletteColour(1), false};
  spec.panels = {Panel{"y", {s, t}}};
  const auto l = chartLayout(spec)[0];
  const cv::Mat img = drawChart(spec);
  const cv::Scalar c = paletteColour(0);
  const cv::Vec3b colour(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
  EXPECT_EQ(img.at<cv::Vec3b>(toPixel(l, 0.5, 0.0)), colour);
  EXPECT_EQ(img.at<cv::Vec3b>(toPixel(l, 3.5, 0.0)), colour);
  EXPECT_NE(img.at<cv::Vec3b>(toPixel(l, 1.5, 0.0)), colour);  // the gap around the NaN
}

TEST(LineChart, ValuesAtNiceNumbersStayOffTheFrameAndSharedAxesAgree) {
  // Openings of exactly 0 and 1 (valves), an ambient line: never on the frame.
  ChartSpec spec;
  spec.shared_y = true;
  spec.panel_height_px = 120;
  spec.panels = {Panel{"a", {Series{"a", {0.0, 1.0}, {0.0, 1.0}, paletteColour(0), false}}},
                 Panel{"b", {Series{"b", {0.0, 1.0}, {0.5, 0.5}, paletteColour(1), false}}, 200}};
  const auto layouts = chartLayout(spec);
  ASSERT_EQ(layouts.size(), 2u);
  for (const auto& l : layouts) {
    EXPECT_LT(l.y.lo, 0.0);
    EXPECT_GT(l.y.hi, 1.0);
    EXPECT_DOUBLE_EQ(l.y.lo, layouts[0].y.lo);  // one scale for small multiples
    EXPECT_DOUBLE_EQ(l.y.hi, layouts[0].y.hi);
  }
  EXPECT_EQ(layouts[1].plot_px.y - layouts[0].plot_px.y, 120);  // panel heights of their own
  EXPECT_EQ(chartHeight(spec), 44 + 120 + 200 + 46);
  EXPECT_EQ(drawChart(spec).rows, chartHeight(spec));
}

/// Pixels of exactly `c` in `img`.
int pixelsOf(const cv::Mat& img, const cv::Scalar& c) {
  const cv::Vec3b colour(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
  int n = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) n += img.at<cv::Vec3b>(y, x) == colour ? 1 : 0;
  return n;
}

TEST(LineChart, AConstantSeriesGetsAReadableRangeNotOneOfAFewNanometres) {
  // P_F of a run without vacuum: 0 mm in every row. The panel shows at least min_span around
  // it, with tick labels of a few digits; without min_span, a unit each side of 0.
  Series zero{"P_F x", {0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, paletteColour(1), false};
  ChartSpec spec;
  spec.panels = {Panel{"P_F x [mm]", {zero}, 200, 2.0}, Panel{"no min_span", {zero}, 200}};
  const auto layouts = chartLayout(spec);
  for (const auto& l : layouts) {
    EXPECT_LE(l.y.lo, -1.0);
    EXPECT_GE(l.y.hi, 1.0);
    EXPECT_GE(l.y.lo, -2.0);
    EXPECT_LE(l.y.hi, 2.0);
    EXPECT_GE(l.y.step, 0.2);
    for (double t : l.y.ticks) EXPECT_LE(tickLabel(t, l.y.step).size(), 4u) << tickLabel(t, l.y.step);
  }
  // A constant 5: +-1 mm around it with min_span 2.
  Series five{"", {0.0, 1.0}, {5.0, 5.0}, paletteColour(1), false};
  spec.panels = {Panel{"y", {five}, 200, 2.0}};
  const auto l5 = chartLayout(spec)[0];
  EXPECT_LE(l5.y.lo, 4.0);
  EXPECT_GE(l5.y.hi, 6.0);
  EXPECT_GT(l5.y.lo, 3.0);
  // A series wider than min_span keeps its own range.
  Series wide{"", {0.0, 1.0}, {-10.0, 10.0}, paletteColour(1), false};
  spec.panels = {Panel{"y", {wide}, 200, 2.0}};
  EXPECT_LE(chartLayout(spec)[0].y.lo, -10.0);
}

TEST(LineChart, ClosedValvesStayOnTheZeroToOneScale) {
  ChartSpec spec;
  spec.shared_y = true;
  Panel closed{"valve 1", {Series{"valve 1", {0.0, 1.0}, {0.0, 0.0}, paletteColour(0), false}}, 120};
  closed.y_include = {0.0, 1.0};
  spec.panels = {closed, closed};
  for (const auto& l : chartLayout(spec)) {
    EXPECT_LT(l.y.lo, 0.0);
    EXPECT_GT(l.y.lo, -0.5);
    EXPECT_GT(l.y.hi, 1.0);
    EXPECT_LT(l.y.hi, 1.5);
  }
}

TEST(RunPlots, ARobotWithoutAReservoirGetsItsPressuresWithoutP_RAndNoValvePlot) {
  // A run directory of the single-chamber robot (no reservoir, no valves): its trace has
  // p1_pa and no pr_pa or valve columns, as the recorder writes it.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "climbsim-plot-no-reservoir-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(std::string(CLIMBSIM_ROBOTS_DIR) + "/../scenarios/hold-single-chamber.yaml",
                             dir / "scenario.yaml");
  const RobotGeometry geometry =
      computeGeometry(loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/single-chamber.yaml"));
  ASSERT_FALSE(geometry.has_reservoir);
  std::string header = "t_s,downforce_n,pf_x_m,pf_y_m,p1_pa";
  std::string values = "700,0,0,96000";
  for (const auto& segment : geometry.segments) {
    header += ",leak_area_m2_" + segment.name;
    values += ",0.0001";
  }
  header += ",x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad";
  values += ",1,1,0,0,0,0";
  for (const char* kind : {"_normal_n", "_slip_mps"}) {
    for (std::size_t w = 1; w <= geometry.wheels.size(); ++w) {
      header += ",wheel" + std::to_string(w) + kind;
      values += ",100";
    }
  }
  header += ",downforce_setpoint_n\n";
  std::ofstream trace(dir / "trace.csv");
  trace << header;
  for (int k = 0; k < 5; ++k) trace << k * 0.5 << "," << values << ",700\n";
  trace.close();
  const auto written = writeRunPlots(dir.string(), (dir / "plots").string());
  const auto has = [&](const std::string& name) {
    return std::any_of(written.begin(), written.end(), [&](const std::string& f) {
      return std::filesystem::path(f).filename() == name;
    });
  };
  EXPECT_TRUE(has("pressures.png"));
  EXPECT_TRUE(has("downforce.png"));
  EXPECT_TRUE(has("wheel_loads.png"));
  EXPECT_FALSE(has("valves.png")) << "a robot without valves has no valve plot";
  // One panel (p1) where a robot with a reservoir also gets p_R's: a lower picture.
  const auto table = TraceTable::parse("t_s,p1_pa,pr_pa\n0,96000,90000\n1,96000,90000\n", "p.csv");
  EXPECT_LT(pressuresPlot(table, 1, 0, false, 1e5).rows, pressuresPlot(table, 1, 0, true, 1e5).rows);
  std::filesystem::remove_all(dir);
}

TEST(RunPlots, WithoutAControllerTheDownforcePlotDrawsNoSetPointAndSaysSo) {
  const RobotDescription robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
  Scenario scenario;
  scenario.controller.kind = Scenario::ControllerKind::kNone;
  const Setpoint none = downforceSetpoint(scenario, robot);
  EXPECT_TRUE(std::isnan(none.downforce_n));
  EXPECT_NE(none.label.find("no set-point"), std::string::npos) << none.label;
  scenario.controller.kind = Scenario::ControllerKind::kFixed;
  EXPECT_TRUE(std::isnan(downforceSetpoint(scenario, robot).downforce_n));
  scenario.controller.kind = Scenario::ControllerKind::kReference;
  scenario.controller.downforce_n = 1500.0;
  EXPECT_EQ(downforceSetpoint(scenario, robot).downforce_n, 1500.0);

  // F of a robot without vacuum (0 N, P_F at the centre), no set-point published (0 in the
  // column): no dashed set-point line anywhere, neither in the plot nor in the legend.
  const auto trace = TraceTable::parse(
      "t_s,downforce_n,pf_x_m,pf_y_m,downforce_setpoint_n\n0,0,0,0,0\n1,0,0,0,0\n2,0,0,0,0\n", "none.csv");
  EXPECT_EQ(pixelsOf(downforcePlot(trace, none.downforce_n, none.label, 631.0), paletteColour(3)), 0);
  EXPECT_GT(pixelsOf(downforcePlot(trace, 1500.0, "set-point", 631.0), paletteColour(3)), 100) << "the reference's line";
}

TEST(SealingPicture, TurnedWallUpWithTimeScaleAndLegend) {
  // A raw picture (robot frame: x right, y up) with a red mark at its +x edge.
  cv::Mat raw(64, 64, CV_8UC3, cv::Scalar(128, 128, 128));
  raw(cv::Rect(58, 30, 6, 4)).setTo(cv::Scalar(0, 0, 255));
  SealingPictureInfo info;
  info.kind = "edges";
  info.t_s = 5.0;
  info.pixel_size_m = 0.8 / 64;
  const auto redCentre = [](const cv::Mat& img) {
    cv::Mat mask;
    cv::inRange(img(cv::Rect(0, 40, 600, 600)), cv::Scalar(0, 0, 250), cv::Scalar(10, 10, 255), mask);
    const cv::Moments m = cv::moments(mask, true);
    return cv::Point2d(m.m10 / m.m00, 40 + m.m01 / m.m00);
  };
  const cv::Mat flat = annotateSealingPicture(raw, info);
  EXPECT_EQ(flat.cols, 900);
  EXPECT_EQ(flat.rows, 670);
  const cv::Point2d centre(300, 340);
  EXPECT_GT(redCentre(flat).x, centre.x + 100);  // yaw 0: robot x is to the right
  info.yaw_rad = -M_PI / 2;                      // robot x points down the wall
  const cv::Point2d down = redCentre(annotateSealingPicture(raw, info));
  EXPECT_GT(down.y, centre.y + 100) << down;
  EXPECT_NEAR(down.x, centre.x, 10.0) << down;
}

double luminance(const cv::Vec3b& bgr) { return 0.114 * bgr[0] + 0.587 * bgr[1] + 0.299 * bgr[2]; }

TEST(RingPicture, ColourBrightensWithPressure) {
  const RingScales scales{80e3, 101325.0, 500.0};
  double last = -1.0;
  for (double p = 80e3; p <= 101325.0; p += 250.0) {
    const double y = luminance(pressureColour(p, scales));
    EXPECT_GE(y, last) << p;
    last = y;
  }
  EXPECT_EQ(pressureColour(50e3, scales), pressureColour(80e3, scales));  // clamped
  EXPECT_GT(luminance(pressureColour(101325.0, scales)), luminance(pressureColour(80e3, scales)) + 100.0);
}

TEST(RingPicture, ChambersAreColouredMonotoneInTheirPressure) {
  const RobotDescription robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
  const RobotGeometry g = computeGeometry(robot);
  RingMoment m;
  // Chamber 1 lowest .. centre highest, in a shuffled geometric order to test the mapping.
  const std::vector<double> p = {84e3, 96e3, 88e3, 100e3, 92e3, 86e3, 98e3};
  ASSERT_EQ(g.chambers.size(), p.size());
  m.chamber_pa = p;
  m.reservoir_pa = 70e3;
  m.wheel_normal_n = {0.0, 0.0, 0.0};
  m.pf_x_m = 0.3;  // out of the way of the sampled points
  m.pf_y_m = 0.3;
  const RingScales scales{80e3, 101325.0, 500.0};
  const cv::Mat img = drawRingPicture(g, robot.body.diameter_m, m, scales);
  const RingLayout l = ringLayout(g, robot.body.diameter_m);
  std::vector<std::pair<double, double>> pressure_luminance;
  for (std::size_t i = 0; i < g.chambers.size(); ++i) {
    const auto& ch = g.chambers[i];
    RobotGeometry::Point at{-0.06, -0.06};  // centre disc: off the x arrow, P_F and the label
    if (ch.span_rad < 6.0) {
      const double r = 0.5 * (ch.inner_radius_m + ch.outer_radius_m);
      const double a = ch.centre_angle_rad - 0.3 * ch.span_rad;  // off the wheel and the label
      at = {r * std::cos(a), r * std::sin(a)};
    }
    const cv::Point2d px = ringPixel(l, m.yaw_rad, at);
    const cv::Vec3b got = img.at<cv::Vec3b>(cvRound(px.y), cvRound(px.x));
    EXPECT_EQ(got, pressureColour(p[i], scales)) << "chamber " << ch.number;
    pressure_luminance.emplace_back(p[i], luminance(got));
  }
  std::sort(pressure_luminance.begin(), pressure_luminance.end());
  for (std::size_t i = 1; i < pressure_luminance.size(); ++i) {
    EXPECT_GT(pressure_luminance[i].second, pressure_luminance[i - 1].second);
  }
}

TEST(RingPicture, AChamberWithoutAValueIsNotDrawnAsDeepVacuum) {
  const RobotDescription robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
  const RobotGeometry g = computeGeometry(robot);
  RingMoment m;
  m.chamber_pa = std::vector<double>(g.chambers.size(), NAN);
  const RingScales scales{80e3, 100e3, 500.0};
  const cv::Mat img = drawRingPicture(g, robot.body.diameter_m, m, scales);
  const auto& ch = g.chambers[0];
  const double r = 0.5 * (ch.inner_radius_m + ch.outer_radius_m), a = ch.centre_angle_rad - 0.3 * ch.span_rad;
  const cv::Point2d px = ringPixel(ringLayout(g, robot.body.diameter_m), 0.0, {r * std::cos(a), r * std::sin(a)});
  const cv::Vec3b got = img.at<cv::Vec3b>(cvRound(px.y), cvRound(px.x));
  for (double p = 80e3; p <= 100e3; p += 500.0) EXPECT_NE(got, pressureColour(p, scales)) << p;
}

TEST(RingPicture, YawTurnsTheRobotIntoTheWallsOrientation) {
  const RobotDescription robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
  const RobotGeometry g = computeGeometry(robot);
  const RingLayout l = ringLayout(g, robot.body.diameter_m);
  // yaw -90 degrees: R's x points down the wall, i.e. down in the picture (rows grow).
  const cv::Point2d o = ringPixel(l, -M_PI / 2, {0.0, 0.0});
  const cv::Point2d x = ringPixel(l, -M_PI / 2, {0.1, 0.0});
  EXPECT_NEAR(x.x, o.x, 1e-9);
  EXPECT_NEAR(x.y - o.y, 0.1 * l.px_per_m, 1e-9);
}

TEST(TraceTable, ReadsColumns) {
  const TraceTable t = TraceTable::parse("t_s,a,b\n0,1,2\n0.005,3,-4.5e2\n", "run/trace.csv");
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.column("b"), (std::vector<double>{2.0, -450.0}));
  EXPECT_EQ(t.rowNearest(0.004), 1u);
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TraceTable, BadInputIsOneLineNamingFileLineColumnAndValue) {
  const std::string bad_cell = errorOf([] { TraceTable::parse("t_s,a\n0,1\n0.005,x1\n", "run/trace.csv"); });
  EXPECT_NE(bad_cell.find("run/trace.csv:3"), std::string::npos) << bad_cell;
  EXPECT_NE(bad_cell.find("column a"), std::string::npos) << bad_cell;
  EXPECT_NE(bad_cell.find("'x1'"), std::string::npos) << bad_cell;
  EXPECT_EQ(bad_cell.find('\n'), std::string::npos);

  const std::string trailing = errorOf([] { TraceTable::parse("t_s,a\n0,1.5kPa\n", "tr.csv"); });
  EXPECT_NE(trailing.find("tr.csv:2: column a = '1.5kPa'"), std::string::npos) << trailing;

  const std::string cells = errorOf([] { TraceTable::parse("t_s,a\n0,1,2\n", "tr.csv"); });
  EXPECT_NE(cells.find("tr.csv:2: 3 cells, the header has 2"), std::string::npos) << cells;

  const TraceTable t = TraceTable::parse("t_s,a\n0,1\n", "tr.csv");
  const std::string missing = errorOf([&] { t.column("downforce_n"); });
  EXPECT_NE(missing.find("tr.csv:1: no column 'downforce_n'"), std::string::npos) << missing;

  const std::string no_file = errorOf([] { TraceTable::read("/nonexistent/run/trace.csv"); });
  EXPECT_NE(no_file.find("/nonexistent/run/trace.csv: cannot read"), std::string::npos) << no_file;

  const std::string empty = errorOf([] { TraceTable::parse("", "tr.csv"); });
  EXPECT_NE(empty.find("tr.csv:1"), std::string::npos) << empty;
}

TEST(PictureNames, ShortestTimeLabels) {
  EXPECT_EQ(pictureTimeLabel(1.0), "1");
  EXPECT_EQ(pictureTimeLabel(2.5), "2.5");
  EXPECT_EQ(pictureTimeLabel(0.125), "0.125");
  EXPECT_EQ(pictureTimeLabel(0.0), "0");
  EXPECT_EQ(ringPictureName(7.0), "ring_7s.png");
  EXPECT_EQ(sealingPictureName("gaps", 12.5), "sealing_gaps_12.5s.png");
}

}  // namespace
}  // namespace climbsim::plot

namespace climbsim::recorder {
namespace {

TEST(SealingPictureFiles, APictureServesEveryEarlierRequestedTimeOfItsKindOnce) {
  SealingPictureFiles files({7.0, 1.0, 1.002, 12.0});
  EXPECT_EQ(files.missingUpTo(secondsToNs(20.0)), 8u);
  // The sealing's first due step at or after 1 s and 1.002 s is 1.005 s: both get it.
  EXPECT_EQ(files.filesFor("edges", secondsToNs(1.005)),
            (std::vector<std::string>{"sealing_edges_1s.png", "sealing_edges_1.002s.png"}));
  EXPECT_TRUE(files.filesFor("edges", secondsToNs(1.005)).empty());  // a duplicate delivery
  EXPECT_EQ(files.filesFor("gaps", secondsToNs(1.005)),
            (std::vector<std::string>{"sealing_gaps_1s.png", "sealing_gaps_1.002s.png"}));
  EXPECT_TRUE(files.filesFor("depth", secondsToNs(1.005)).empty());  // unknown kind
  EXPECT_EQ(files.missingUpTo(secondsToNs(7.0)), 2u);
  EXPECT_EQ(files.filesFor("gaps", secondsToNs(7.01)), (std::vector<std::string>{"sealing_gaps_7s.png"}));
  EXPECT_EQ(files.missingUpTo(secondsToNs(7.0)), 1u);
  EXPECT_EQ(files.missingUpTo(secondsToNs(12.0)), 3u);
  EXPECT_EQ(files.written(), 5u);
}

TEST(SealingPictureFiles, ExactTimeIsAtOrAfter) {
  SealingPictureFiles files({2.0});
  EXPECT_TRUE(files.filesFor("edges", secondsToNs(1.995)).empty());
  EXPECT_EQ(files.filesFor("edges", secondsToNs(2.0)).size(), 1u);
}

}  // namespace
}  // namespace climbsim::recorder

namespace climbsim::plot {
namespace {

TEST(RunPlots, ThePlottedSetPointIsTheOneTheControllerPublished) {
  // An external controller stating 1800 N from the second row on: the plot draws its set-point
  // (with a gap where none was stated), not the robot file's.
  const auto trace = TraceTable::parse("t_s,downforce_n,downforce_setpoint_n\n0,0,0\n0.005,10,1800\n0.01,20,1800\n",
                                       "published.csv");
  const Series s = publishedSetpoint(trace);
  ASSERT_EQ(s.y.size(), 3u);
  EXPECT_TRUE(std::isnan(s.y[0]));
  EXPECT_EQ(s.y[1], 1800.0);
  EXPECT_EQ(s.y[2], 1800.0);
  EXPECT_TRUE(s.dashed);
  EXPECT_NE(s.label.find("controller"), std::string::npos);
  // No set-point stated in any row, or an older trace without the column: nothing published.
  EXPECT_TRUE(publishedSetpoint(TraceTable::parse("t_s,downforce_setpoint_n\n0,0\n1,0\n", "none.csv")).x.empty());
  EXPECT_TRUE(publishedSetpoint(TraceTable::parse("t_s,downforce_n\n0,0\n", "old.csv")).x.empty());
}

}  // namespace
}  // namespace climbsim::plot
