#include "climbsim/wall_patches/surface_features.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "climbsim/wall_patches/seeded_random.hpp"

namespace climbsim::surface {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::Vector2d direction(double angle_deg) {
  const double a = angle_deg * M_PI / 180.0;
  return {std::cos(a), std::sin(a)};
}

Eigen::Vector2d leftNormal(const Eigen::Vector2d& dir) { return {-dir.y(), dir.x()}; }


/// Inserts breakpoints on the linear pieces so that none is wider than max_gap.
void densify(ProfileBreakpoints& p, double max_gap) {
  ProfileBreakpoints out;
  for (std::size_t k = 0; k < p.s_m.size(); ++k) {
    if (k > 0) {
      const double gap = p.s_m[k] - p.s_m[k - 1];
      const int pieces = static_cast<int>(std::ceil(gap / max_gap - 1e-9));
      for (int i = 1; i < pieces; ++i) {
        const double f = static_cast<double>(i) / pieces;
        out.s_m.push_back(p.s_m[k - 1] + f * gap);
        out.depth_fraction.push_back(p.depth_fraction[k - 1] + f * (p.depth_fraction[k] - p.depth_fraction[k - 1]));
      }
    }
    out.s_m.push_back(p.s_m[k]);
    out.depth_fraction.push_back(p.depth_fraction[k]);
  }
  p = out;
}

}  // namespace

double Depression::distance(const Eigen::Vector2d& p_m) const {
  if (polygon_sides > 0) {
    const Eigen::Vector2d d = p_m - centre.origin;
    const double sector = 2.0 * M_PI / polygon_sides;
    const double nearest = sector * std::round(std::atan2(d.y(), d.x()) / sector);
    return d.x() * std::cos(nearest) + d.y() * std::sin(nearest);
  }
  const double t = std::clamp(centre.dir.dot(p_m - centre.origin), centre.t_begin, centre.t_end);
  return (p_m - (centre.origin + t * centre.dir)).norm();
}

double ProfileBreakpoints::at(double s) const {
  if (s >= s_m.back()) return 0.0;
  if (s <= s_m.front()) return depth_fraction.front();
  const auto upper = std::upper_bound(s_m.begin(), s_m.end(), s);
  const std::size_t k = static_cast<std::size_t>(upper - s_m.begin());
  const double f = (s - s_m[k - 1]) / (s_m[k] - s_m[k - 1]);
  return depth_fraction[k - 1] + f * (depth_fraction[k] - depth_fraction[k - 1]);
}

ProfileBreakpoints linearProfile(Profile profile, double width_m, double wall_run_m) {
  const double half = 0.5 * width_m;
  ProfileBreakpoints p;
  switch (profile) {
    case Profile::kRect: {
      const double run = std::min(wall_run_m, width_m / 10.0);
      p.s_m = {0.0, half - run, half};
      p.depth_fraction = {1.0, 1.0, 0.0};
      break;
    }
    case Profile::kV:
      p.s_m = {0.0, half};
      p.depth_fraction = {1.0, 0.0};
      break;
    case Profile::kU: {
      constexpr int kPieces = 8;
      for (int k = 0; k <= kPieces; ++k) {
        const double f = static_cast<double>(k) / kPieces;
        p.s_m.push_back(f * half);
        p.depth_fraction.push_back(std::sqrt(std::max(0.0, 1.0 - f * f)));
      }
      break;
    }
  }
  densify(p, width_m / 4.0);
  return p;
}

SurfaceFeatures::SurfaceFeatures(const PatchSpec& spec, std::uint64_t network_seed, double grid_m) {
  for (const LinearFeature& f : spec.cracks) addLinear(f, spec.wall_run_m);
  for (const LinearFeature& f : spec.grooves) addLinear(f, spec.wall_run_m);
  addNetwork(spec, network_seed);
  for (const Hole& h : spec.holes) addHole(h, spec.wall_run_m, grid_m);
  for (const Step& s : spec.steps) {
    StepFeature step;
    step.origin = {s.x_m, s.y_m};
    step.dir = direction(s.angle_deg);
    step.height_m = s.height_m;
    step.run_m = spec.wall_run_m;
    steps_.push_back(step);
    for (double offset : {-0.5 * step.run_m, 0.5 * step.run_m})
      cuts_.push_back({step.origin + offset * leftNormal(step.dir), step.dir, -kInf, kInf});
  }
}

void SurfaceFeatures::addLinear(const LinearFeature& f, double wall_run_m) {
  const Eigen::Vector2d centre(f.x_m, f.y_m), dir = direction(f.angle_deg);
  if (f.length_m > 0.0) {
    addSegmentDepression(centre - 0.5 * f.length_m * dir, centre + 0.5 * f.length_m * dir, f.width_m, f.depth_m,
                         f.profile, wall_run_m);
    return;
  }
  Depression d;
  d.centre = {centre, dir, -kInf, kInf};
  d.depth_m = f.depth_m;
  d.profile = linearProfile(f.profile, f.width_m, wall_run_m);
  for (std::size_t k = 0; k < d.profile.s_m.size(); ++k)
    for (double sign : {-1.0, 1.0}) {
      if (d.profile.s_m[k] == 0.0 && sign > 0) continue;
      cuts_.push_back({centre + sign * d.profile.s_m[k] * leftNormal(dir), dir, -kInf, kInf});
    }
  depressions_.push_back(d);
}

void SurfaceFeatures::addSegmentDepression(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double width_m,
                                           double depth_m, Profile profile, double wall_run_m) {
  const double length = (to - from).norm();
  if (length <= 0.0) return;
  Depression d;
  d.centre = {from, (to - from) / length, 0.0, length};
  d.depth_m = depth_m;
  d.profile = linearProfile(profile, width_m, wall_run_m);
  for (std::size_t k = 0; k < d.profile.s_m.size(); ++k)
    for (double sign : {-1.0, 1.0}) {
      if (d.profile.s_m[k] == 0.0 && sign > 0) continue;
      cuts_.push_back({from + sign * d.profile.s_m[k] * leftNormal(d.centre.dir), d.centre.dir, 0.0, length});
    }
  depressions_.push_back(d);
}

void SurfaceFeatures::addHole(const Hole& hole, double wall_run_m, double grid_m) {
  const double radius = 0.5 * hole.diameter_m;
  const double run = std::min(wall_run_m, radius / 5.0);
  // Sides no longer than half a grid cell and close to the circle (corners at most run / 2
  // outside it), a multiple of 4 so that sides touch the circle on the x and y axes.
  const double by_length = 2.0 * M_PI * radius / (0.5 * grid_m);
  const double by_corner = M_PI / std::acos(radius / (radius + 0.5 * run));
  const int sides = std::clamp(4 * static_cast<int>(std::ceil(std::max(by_length, by_corner) / 4.0)), 16, 4096);
  Depression d;
  d.centre = {{hole.x_m, hole.y_m}, Eigen::Vector2d::UnitX(), 0.0, 0.0};
  d.depth_m = hole.depth_m;
  d.profile.s_m = {0.0, radius - run, radius};
  d.profile.depth_fraction = {1.0, 1.0, 0.0};
  d.polygon_sides = sides;
  depressions_.push_back(d);
  const double half = M_PI / sides;
  const auto corner = [&](double apothem, int k) {
    const double a = (2 * k + 1) * half;
    return Eigen::Vector2d(d.centre.origin + apothem / std::cos(half) * Eigen::Vector2d(std::cos(a), std::sin(a)));
  };
  const auto add = [&](const Eigen::Vector2d& p0, const Eigen::Vector2d& p1) {
    const double length = (p1 - p0).norm();
    cuts_.push_back({p0, (p1 - p0) / length, 0.0, length});
  };
  // The rim (apothem r), the floor's edge (apothem r - run) and the sector borders between
  // them, where the gauge switches from one side's normal to the next.
  for (int k = 0; k < sides; ++k) {
    add(corner(radius, k - 1), corner(radius, k));
    add(corner(radius - run, k - 1), corner(radius - run, k));
    add(corner(radius - run, k), corner(radius, k));
  }
}

void SurfaceFeatures::addNetwork(const PatchSpec& spec, std::uint64_t seed) {
  const CrackNetwork& n = spec.network;
  SeededRandom random(seed);
  const double size = spec.size_m;
  for (int c = 0; c < n.count; ++c) {
    Eigen::Vector2d p(random.uniform(0.0, size), random.uniform(0.0, size));
    double angle = random.uniform(0.0, 2.0 * M_PI);
    std::vector<Eigen::Vector2d> line{p};
    for (int s = 0; s < n.segments; ++s) {
      if (s > 0) angle += n.turn_deg * M_PI / 180.0 * random.normal();
      const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
      // Clipped at the face border, where the polyline ends.
      double length = n.segment_length_m;
      for (int axis = 0; axis < 2; ++axis) {
        if (dir[axis] > 0) length = std::min(length, (size - p[axis]) / dir[axis]);
        if (dir[axis] < 0) length = std::min(length, -p[axis] / dir[axis]);
      }
      const Eigen::Vector2d q = p + length * dir;
      addSegmentDepression(p, q, n.width_m, n.depth_m, n.profile, spec.wall_run_m);
      line.push_back(q);
      p = q;
      if (length < n.segment_length_m) break;
    }
    polylines_.push_back(line);
  }
}

double SurfaceFeatures::heightOffset(const Eigen::Vector2d& p_m) const {
  double offset = 0.0;
  for (const StepFeature& s : steps_) {
    const double across = leftNormal(s.dir).dot(p_m - s.origin);
    offset += s.height_m * std::clamp((across + 0.5 * s.run_m) / s.run_m, 0.0, 1.0);
  }
  double deepest = 0.0;
  for (const Depression& d : depressions_) {
    const double s = d.distance(p_m);
    if (s < d.profile.s_m.back()) deepest = std::max(deepest, d.depth_m * d.profile.at(s));
  }
  return offset - deepest;
}

}  // namespace climbsim::surface
