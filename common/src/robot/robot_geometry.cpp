#include "climbsim/robot/robot_geometry.hpp"

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
  for (const Point& p : arc(r1, start_rad + theta, -theta)) c.outline_Robot.push_back(p);
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

void addSegments(RobotGeometry& g) {
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
  for (int i = 1; i <= n; ++i) {
    const double start_rad = (i - 1) * theta - theta / 2.0;
    g.segments.push_back(segment("inner" + std::to_string(i), Kind::kInner, i - 1, g.centreChamber(), r1 * theta,
                                 arc(r1, start_rad, theta)));
  }
}

}  // namespace

double RobotGeometry::volumeOf(VolumeId id) const {
  if (id == reservoir()) return reservoir_volume_m3;
  if (id >= 0 && id < static_cast<int>(chambers.size())) return chambers[id].volume_m3;
  throw std::out_of_range("RobotGeometry::volumeOf: no volume with id " + std::to_string(id));
}

std::string RobotGeometry::volumeName(VolumeId id) const {
  if (id == kAmbient) return "o";
  if (id == reservoir()) return "R";
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

RobotGeometry computeGeometry(const RobotDescription& d) {
  RobotGeometry g;
  g.outer_count = d.chambers.outer_count;
  g.sector_angle_rad = 2.0 * kPi / g.outer_count;
  g.centre_radius_m = d.chambers.centre_radius_m;
  g.ring_outer_radius_m = d.body.sealed_diameter_m / 2.0;
  g.strip_width_m = d.sealing.strip_width_m;
  g.reservoir_volume_m3 = d.reservoir.volume_m3;
  for (int number = 1; number <= g.outer_count; ++number) {
    g.chambers.push_back(sector(g, number, d.chambers.outer_volume_m3));
  }
  g.chambers.push_back(centreDisc(g, d.chambers.centre_volume_m3));
  addSegments(g);
  for (const int number : d.wheels.chambers) {
    const double angle_rad = g.chambers.at(number - 1).centre_angle_rad;
    g.wheels.push_back(RobotGeometry::Wheel{number, angle_rad, polar(d.wheels.mount_radius_m, angle_rad)});
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
