#include "climbsim/robot/robot_picture.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace climbsim::robot {

namespace {

using Point = RobotGeometry::Point;
using Kind = RobotDescription::WheelKind;

const cv::Scalar kInk(40, 40, 40);
const cv::Scalar kBody(225, 225, 225);
const cv::Scalar kStrip(60, 60, 200);       // red-ish (BGR): outer strips
const cv::Scalar kWall(200, 120, 40);       // blue-ish: strips between chambers
const cv::Scalar kWheel(30, 30, 30);
const cv::Scalar kAir(40, 140, 40);         // green: reservoir, valves, engines

/// A soft colour per chamber, repeating every 6.
cv::Scalar chamberColour(int number) {
  static const cv::Scalar colours[] = {{250, 230, 200}, {210, 245, 210}, {200, 230, 250},
                                       {240, 210, 240}, {200, 245, 245}, {230, 230, 200}};
  return colours[(number - 1) % 6];
}

/// Maps robot-frame metres to pixels: x to the right, y up, origin at `centre`.
struct View {
  cv::Point2d centre;
  double px_per_m = 1.0;
  cv::Point at(Point p) const {
    return cv::Point(static_cast<int>(std::lround(centre.x + p.x_m * px_per_m)),
                     static_cast<int>(std::lround(centre.y - p.y_m * px_per_m)));
  }
  std::vector<cv::Point> at(const std::vector<Point>& line) const {
    std::vector<cv::Point> out;
    for (const auto& p : line) out.push_back(at(p));
    return out;
  }
};

void label(cv::Mat& img, const std::string& text, cv::Point at, double scale, const cv::Scalar& colour, int thickness = 1) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline);
  cv::putText(img, text, at - cv::Point(size.width / 2, -size.height / 2), cv::FONT_HERSHEY_SIMPLEX, scale, colour,
              thickness, cv::LINE_AA);
}

Point midpoint(const std::vector<Point>& line) {
  double total = 0.0;
  for (std::size_t k = 1; k < line.size(); ++k) total += std::hypot(line[k].x_m - line[k - 1].x_m, line[k].y_m - line[k - 1].y_m);
  double walked = 0.0;
  for (std::size_t k = 1; k < line.size(); ++k) {
    const double step = std::hypot(line[k].x_m - line[k - 1].x_m, line[k].y_m - line[k - 1].y_m);
    if (walked + step >= total / 2.0 && step > 0.0) {
      const double t = (total / 2.0 - walked) / step;
      return {line[k - 1].x_m + t * (line[k].x_m - line[k - 1].x_m), line[k - 1].y_m + t * (line[k].y_m - line[k - 1].y_m)};
    }
    walked += step;
  }
  return line.front();
}

void drawWheel(cv::Mat& img, const View& v, const RobotGeometry::Wheel& w, int index) {
  const cv::Point c = v.at(w.p_RobotWheel);
  const int r = std::max(4, static_cast<int>(std::lround(w.radius_m * v.px_per_m)));
  const int half_width = std::max(3, r / 3);
  switch (w.kind) {
    case Kind::kSteerable:  // a tyre seen from outside, with a ring: it turns about the normal
      cv::circle(img, c, r, kWheel, 2, cv::LINE_AA);
      cv::rectangle(img, c - cv::Point(r, half_width), c + cv::Point(r, half_width), kWheel, cv::FILLED);
      break;
    case Kind::kFixed:  // a tyre along x
      cv::rectangle(img, c - cv::Point(r, half_width), c + cv::Point(r, half_width), kWheel, cv::FILLED);
      cv::line(img, c - cv::Point(0, 2 * half_width), c + cv::Point(0, 2 * half_width), kWheel, 2, cv::LINE_AA);
      break;
    case Kind::kCaster:  // a small open wheel
      cv::circle(img, c, std::max(4, r / 2), kWheel, 2, cv::LINE_AA);
      cv::circle(img, c, 2, kWheel, cv::FILLED);
      break;
  }
  label(img, "W" + std::to_string(index + 1), c + cv::Point(0, r + 14), 0.5, kWheel, 1);
}

/// The air path on the right: the reservoir with its valves to every chamber and the engines
/// on it, or each engine on its chamber.
void drawAirPath(cv::Mat& img, const View& v, const RobotDescription& d, const RobotGeometry& g, int x0, int y0) {
  // The reservoir next to the robot, the engines right of it, the valves to the left.
  const auto engineBox = [&](int i) {
    const cv::Point top_left(x0 + 170, y0 + 120 + i * 34);
    cv::rectangle(img, top_left, top_left + cv::Point(90, 26), kAir, 2);
    label(img, "engine " + std::to_string(i + 1), top_left + cv::Point(45, 13), 0.45, kAir);
    return top_left + cv::Point(0, 13);
  };
  if (g.has_reservoir) {
    const cv::Point r_top(x0 + 20, y0 + 120);
    const cv::Point r_bottom = r_top + cv::Point(110, std::max(60, 34 * d.engines.count - 8));
    cv::rectangle(img, r_top, r_bottom, kAir, 2);
    label(img, "reservoir", (r_top + r_bottom) / 2 - cv::Point(0, 10), 0.5, kAir);
    label(img, std::to_string(static_cast<int>(std::lround(d.reservoir.volume_m3 * 1e3))) + " L",
          (r_top + r_bottom) / 2 + cv::Point(0, 12), 0.5, kAir);
    for (int i = 0; i < d.engines.count; ++i) {
      const cv::Point e = engineBox(i);
      cv::arrowedLine(img, cv::Point(r_bottom.x, e.y), e, kAir, 1, cv::LINE_AA, 0, 0.2);
    }
    // One valve from the reservoir to every chamber.
    const cv::Point from(r_top.x, (r_top.y + r_bottom.y) / 2);
    for (const auto& c : g.chambers) {
      cv::line(img, from, v.at(c.p_RobotCentroid), kAir, 1, cv::LINE_AA);
      cv::circle(img, v.at(c.p_RobotCentroid), 4, kAir, cv::FILLED);
    }
    label(img, std::to_string(g.chamberCount()) + " valves, reservoir to each chamber", cv::Point(x0 + 200, y0 + 70),
          0.45, kAir);
  } else {
    for (int i = 0; i < d.engines.count; ++i) {
      const cv::Point e = engineBox(i);
      const auto& c = g.chambers.at(static_cast<std::size_t>(d.engines.chambers.at(static_cast<std::size_t>(i)) - 1));
      cv::arrowedLine(img, v.at(c.p_RobotCentroid), e, kAir, 1, cv::LINE_AA, 0, 0.03);
    }
    label(img, "no reservoir: each engine pumps its chamber", cv::Point(x0 + 200, y0 + 70), 0.45, kAir);
  }
}

std::string count(int n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

void drawLegend(cv::Mat& img, const RobotDescription& d, const RobotGeometry& g, int x0, int y) {
  const auto line = [&](const std::string& text) {
    cv::putText(img, text, cv::Point(x0 + 10, y), cv::FONT_HERSHEY_SIMPLEX, 0.5, kInk, 1, cv::LINE_AA);
    y += 22;
  };
  line(std::string("layout ") + toString(d.chambers.layout) + ", " + count(g.chamberCount(), "chamber") + ", " +
       count(static_cast<int>(g.segments.size()), "sealing segment"));
  int steerable = 0, fixed = 0, caster = 0;
  for (const auto& w : g.wheels) {
    steerable += w.kind == Kind::kSteerable;
    fixed += w.kind == Kind::kFixed;
    caster += w.kind == Kind::kCaster;
  }
  line(count(static_cast<int>(g.wheels.size()), "wheel") + ": " + std::to_string(steerable) + " steerable (ringed), " +
       std::to_string(fixed) + " fixed, " + std::to_string(caster) + " caster (open)");
  line("strips: red to the outside, blue between chambers");
}

/// Where a chamber's number goes: its centroid, moved towards the origin (or up, for the
/// chamber at the origin) when a wheel sits there.
Point numberPlace(const RobotGeometry& g, const RobotGeometry::Chamber& c) {
  Point at = c.p_RobotCentroid;
  for (const auto& w : g.wheels) {
    if (std::hypot(w.p_RobotWheel.x_m - at.x_m, w.p_RobotWheel.y_m - at.y_m) > 2.0 * w.radius_m) continue;
    const double r = std::hypot(at.x_m, at.y_m);
    const double shift_m = 2.5 * w.radius_m;
    if (r > shift_m) return {at.x_m * (1.0 - shift_m / r), at.y_m * (1.0 - shift_m / r)};
    return {at.x_m, at.y_m + shift_m};
  }
  return at;
}

}  // namespace

cv::Mat drawRobot(const RobotDescription& d, const RobotGeometry& g, int width_px) {
  const int robot_px = width_px * 3 / 5;
  const int height_px = std::max(robot_px, 520);
  cv::Mat img(height_px, width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  View v;
  v.centre = cv::Point2d(robot_px / 2.0, height_px / 2.0);
  v.px_per_m = 0.92 * robot_px / (2.0 * d.body.outerRadius());

  cv::fillPoly(img, std::vector<std::vector<cv::Point>>{v.at(g.body_outline_Robot)}, kBody, cv::LINE_AA);
  for (const auto& c : g.chambers) {
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{v.at(c.outline_Robot)}, chamberColour(c.number), cv::LINE_AA);
  }
  const int strip_px = std::max(2, static_cast<int>(std::lround(g.strip_width_m * v.px_per_m)));
  for (const auto& s : g.segments) {
    const bool outer = s.kind == RobotGeometry::SegmentKind::kOuter;
    cv::polylines(img, v.at(s.centreline_Robot), false, outer ? kStrip : kWall, strip_px, cv::LINE_AA);
  }
  for (const auto& s : g.segments) {
    label(img, s.name, v.at(midpoint(s.centreline_Robot)), 0.35, cv::Scalar(255, 255, 255), 1);
  }
  for (const auto& c : g.chambers) label(img, std::to_string(c.number), v.at(numberPlace(g, c)), 0.8, kInk, 2);
  for (std::size_t i = 0; i < g.wheels.size(); ++i) drawWheel(img, v, g.wheels[i], static_cast<int>(i));
  // Axes of the robot frame.
  cv::arrowedLine(img, v.at(Point{0, 0}), v.at(Point{0.08, 0}), kInk, 1, cv::LINE_AA, 0, 0.2);
  cv::arrowedLine(img, v.at(Point{0, 0}), v.at(Point{0, 0.08}), kInk, 1, cv::LINE_AA, 0, 0.2);
  label(img, d.name, cv::Point(robot_px / 2, 22), 0.7, kInk, 2);

  drawAirPath(img, v, d, g, robot_px, 0);
  drawLegend(img, d, g, robot_px, height_px - 80);
  return img;
}

}  // namespace climbsim::robot
