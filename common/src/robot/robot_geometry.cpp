#include "climbsim/robot/robot_geometry.hpp"

#include "climbsim/robot/chamber_polygons.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace climbsim {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Point = RobotGeometry::Point;

Point polar(double radius_m, double angle_rad) {
  return Point{radius_m * std::cos(angle_rad), radius_m * std::sin(angle_rad)};
}

/// Points of the arc from `from_rad` by `span_rad` (negative: clockwise), both ends included.
std::vector<Point> arc(double radius_m, double from_rad, double span_rad) {
  // The epsilon keeps 60° at 60 intervals despite rounding in 2π/6 / (π/180).
  const int intervals = std::max(1, static_cast<int>(std::ceil(std::abs(span_rad) / kArcSampleStepRad - 1e-9)));
  std::vector<Point> points;
  points.reserve(intervals + 1);
  for (int k = 0; k <= intervals; ++k) {
    points.push_back(polar(radius_m, from_rad + span_rad * k / intervals));
  }
  return points;
}

RobotGeometry::Chamber sector(const RobotGeometry& g, int number, double volume_m3) {
  const double theta = g.sector_angle_rad;
  const double r1 = g.centre_radius_m;
  const double r2 = g.ring_outer_radius_m;
  RobotGeometry::Chamber c;
  c.id = number - 1;
  c.number = number;
  c.volume_m3 = volume_m3;
  c.inner_radius_m = r1;
  c.outer_radius_m = r2;
  c.centre_angle_rad = (number - 1) * theta;
  c.span_rad = theta;
  c.area_m2 = theta / 2.0 * (r2 * r2 - r1 * r1);
  const double half = theta / 2.0;
  const double centroid_radius_m =
      2.0 / 3.0 * (r2 * r2 * r2 - r1 * r1 * r1) / (r2 * r2 - r1 * r1) * std::sin(half) / half;
  c.p_RobotCentroid = polar(centroid_radius_m, c.centre_angle_rad);
  const double start_rad = c.centre_angle_rad - half;
  c.outline_Robot = arc(r2, start_rad, theta);
  if (r1 == 0.0) {
    c.outline_Robot.push_back(Point{0.0, 0.0});  // a pie slice: its tip at the origin
  } else {
    for (const Point& p : arc(r1, start_rad + theta, -theta)) c.outline_Robot.push_back(p);
  }
  return c;
}

RobotGeometry::Chamber centreDisc(const RobotGeometry& g, double volume_m3) {
  RobotGeometry::Chamber c;
  c.id = g.centreChamber();
  c.number = g.outer_count + 1;
  c.volume_m3 = volume_m3;
  c.outer_radius_m = g.centre_radius_m;
  c.span_rad = 2.0 * kPi;
  c.area_m2 = kPi * g.centre_radius_m * g.centre_radius_m;
  c.outline_Robot = arc(g.centre_radius_m, 0.0, 2.0 * kPi);
  c.outline_Robot.pop_back();  // the full circle ends where it starts
  return c;
}

RobotGeometry::SealingSegment segment(std::string name, RobotGeometry::SegmentKind kind, VolumeId a, VolumeId b,
                                      double length_m, std::vector<Point> centreline) {
  return RobotGeometry::SealingSegment{std::move(name), kind, a, b, length_m, std::move(centreline)};
}

void addRingSegments(RobotGeometry& g) {
  using Kind = RobotGeometry::SegmentKind;
  const int n = g.outer_count;
  const double theta = g.sector_angle_rad;
  const double r1 = g.centre_radius_m;
  const double r2 = g.ring_outer_radius_m;
  for (int i = 1; i <= n; ++i) {
    const double start_rad = (i - 1) * theta - theta / 2.0;
    g.segments.push_back(segment("outer" + std::to_string(i), Kind::kOuter, i - 1, kAmbient, r2 * theta,
                                 arc(r2, start_rad, theta)));
  }
  for (int i = 1; i <= n; ++i) {
    const int next = i % n + 1;
    const double wall_rad = (i - 1) * theta + theta / 2.0;
    g.segments.push_back(segment("radial" + std::to_string(i) + "_" + std::to_string(next), Kind::kRadial, i - 1,
                                 next - 1, r2 - r1, {polar(r1, wall_rad), polar(r2, wall_rad)}));
  }
  if (!g.has_centre) return;
  for (int i = 1; i <= n; ++i) {
    const double start_rad = (i - 1) * theta - theta / 2.0;
    g.segments.push_back(segment("inner" + std::to_string(i), Kind::kInner, i - 1, g.centreChamber(), r1 * theta,
                                 arc(r1, start_rad, theta)));
  }
}

}  // namespace

double RobotGeometry::volumeOf(VolumeId id) const {
  if (has_reservoir && id == reservoir()) return reservoir_volume_m3;
  if (id >= 0 && id < static_cast<int>(chambers.size())) return chambers[id].volume_m3;
  throw std::out_of_range("RobotGeometry::volumeOf: no volume with id " + std::to_string(id));
}

std::string RobotGeometry::volumeName(VolumeId id) const {
  if (id == kAmbient) return "o";
  if (has_reservoir && id == reservoir()) return "R";
  if (id >= 0 && id < static_cast<int>(chambers.size())) return std::to_string(chambers[id].number);
  throw std::out_of_range("RobotGeometry::volumeName: no volume with id " + std::to_string(id));
}

std::vector<std::size_t> RobotGeometry::segmentsOf(VolumeId id) const {
  std::vector<std::size_t> found;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (segments[s].volume_a == id || segments[s].volume_b == id) found.push_back(s);
  }
  return found;
}

double RobotGeometry::suctionArea() const {
  double sum_m2 = 0.0;
  for (const auto& c : chambers) sum_m2 += c.area_m2;
  return sum_m2;
}

namespace {

using Description = RobotDescription;

std::vector<Point> rectangle(double x0, double y0, double x1, double y1) {
  return {Point{x0, y0}, Point{x1, y0}, Point{x1, y1}, Point{x0, y1}};
}

std::vector<Point> circle(double radius_m) {
  std::vector<Point> points = arc(radius_m, 0.0, 2.0 * kPi);
  points.pop_back();  // the full circle ends where it starts
  return points;
}

std::vector<Point> shapeOutline(Description::Shape shape, double diameter_m, double length_m, double width_m) {
  if (shape == Description::Shape::kCircle) return circle(diameter_m / 2.0);
  return rectangle(-length_m / 2.0, -width_m / 2.0, length_m / 2.0, width_m / 2.0);
}

void ringChambers(const Description& d, RobotGeometry& g) {
  g.outer_count = d.chambers.count;
  g.has_centre = d.chambers.centre_radius_m > 0.0;
  g.sector_angle_rad = 2.0 * kPi / g.outer_count;
  g.centre_radius_m = d.chambers.centre_radius_m;
  g.ring_outer_radius_m = d.chambers.sealed_diameter_m / 2.0;
  for (int number = 1; number <= g.outer_count; ++number) {
    g.chambers.push_back(sector(g, number, d.chambers.volume_m3));
  }
  if (g.has_centre) g.chambers.push_back(centreDisc(g, d.chambers.centre_volume_m3));
  addRingSegments(g);
}

/// A chamber of a polygon layout: area and centroid from the outline (shoelace).
RobotGeometry::Chamber polygonChamber(int index, std::vector<Point> outline, double volume_m3) {
  RobotGeometry::Chamber c;
  c.id = index;
  c.number = index + 1;
  c.volume_m3 = volume_m3;
  c.outline_Robot = robot::counterClockwise(std::move(outline));
  c.area_m2 = robot::signedArea(c.outline_Robot);
  c.p_RobotCentroid = robot::centroid(c.outline_Robot);
  return c;
}

}  // namespace

std::vector<std::vector<Point>> chamberOutlines(const RobotDescription& d) {
  const auto& c = d.chambers;
  std::vector<std::vector<Point>> out;
  switch (c.layout) {
    case Description::Layout::kRing: {
      RobotGeometry g;
      ringChambers(d, g);
      for (auto& chamber : g.chambers) out.push_back(std::move(chamber.outline_Robot));
      break;
    }
    case Description::Layout::kGrid:
      for (int row = 0; row < c.rows; ++row) {
        for (int column = 0; column < c.columns; ++column) {
          const double x0 = -c.length_m / 2.0 + c.length_m * column / c.columns;
          const double x1 = -c.length_m / 2.0 + c.length_m * (column + 1) / c.columns;
          const double y0 = -c.width_m / 2.0 + c.width_m * row / c.rows;
          const double y1 = -c.width_m / 2.0 + c.width_m * (row + 1) / c.rows;
          out.push_back(rectangle(x0, y0, x1, y1));
        }
      }
      break;
    case Description::Layout::kSingle:
      out.push_back(shapeOutline(c.shape, c.diameter_m, c.length_m, c.width_m));
      break;
    case Description::Layout::kPolygons:
      for (const auto& p : c.polygons) out.push_back(robot::counterClockwise(p.outline));
      break;
  }
  return out;
}

RobotGeometry computeGeometry(const RobotDescription& d) {
  RobotGeometry g;
  g.layout = d.chambers.layout;
  g.strip_width_m = d.sealing.strip_width_m;
  g.has_reservoir = d.reservoir.present;
  g.reservoir_volume_m3 = d.reservoir.present ? d.reservoir.volume_m3 : 0.0;
  g.body_outline_Robot = shapeOutline(d.body.shape, d.body.diameter_m, d.body.length_m, d.body.width_m);
  if (d.chambers.layout == Description::Layout::kRing) {
    ringChambers(d, g);
  } else {
    const auto outlines = chamberOutlines(d);
    for (std::size_t i = 0; i < outlines.size(); ++i) {
      const double volume_m3 = d.chambers.layout == Description::Layout::kPolygons ? d.chambers.polygons[i].volume_m3
                                                                                  : d.chambers.volume_m3;
      g.chambers.push_back(polygonChamber(static_cast<int>(i), outlines[i], volume_m3));
    }
    if (d.chambers.layout == Description::Layout::kSingle && d.chambers.shape == Description::Shape::kCircle) {
      const double r = d.chambers.diameter_m / 2.0;  // the disc's exact area, as for the ring's centre
      g.chambers.front().area_m2 = kPi * r * r;
      g.chambers.front().p_RobotCentroid = Point{0.0, 0.0};
    }
    g.segments = robot::sealingSegments(outlines).segments;
  }
  for (const auto& w : d.wheels) {
    RobotGeometry::Wheel wheel;
    wheel.kind = w.kind;
    wheel.chamber_number = w.chamber;
    wheel.radius_m = w.radius_m;
    wheel.friction_coefficient = w.friction_coefficient;
    if (w.chamber > 0) {
      wheel.angle_rad = g.chambers.at(w.chamber - 1).centre_angle_rad;
      wheel.p_RobotWheel = polar(w.mount_radius_m, wheel.angle_rad);
    } else {
      wheel.p_RobotWheel = Point{w.x_m, w.y_m};
      wheel.angle_rad = std::atan2(w.y_m, w.x_m);
    }
    g.wheels.push_back(wheel);
  }
  return g;
}

std::vector<std::string> segmentNames(const RobotGeometry& geometry) {
  std::vector<std::string> names;
  for (const auto& segment : geometry.segments) names.push_back(segment.name);
  return names;
}

std::vector<double> basicLeakAreas(const RobotDescription& description, const RobotGeometry& geometry) {
  std::vector<double> areas;
  for (const auto& segment : geometry.segments) areas.push_back(segment.length_m * description.sealing.basic_gap_m);
  return areas;
}

}  // namespace climbsim
