// Features measured on the exported and re-imported mesh (assimp), against the asked
// widths, depths, diameters and heights. The crack's depth is measured against the same
// patch without the crack (same seed: the same rough surface).

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "climbsim/wall_patches/mesh_io.hpp"
#include "climbsim/wall_patches/surface_features.hpp"
#include "surface_sampler.hpp"
#include "climbsim/wall_patches/wall_patch.hpp"

namespace climbsim::surface {
namespace {

using test::SurfaceSampler;

constexpr double kHeightTolM = 2e-6;  // float32 coordinates of a 0.5 m patch

PatchSpec smallRoughSpec(std::uint64_t seed) {
  PatchSpec spec;
  spec.size_m = 0.5;
  spec.grid_m = 0.005;
  spec.seed = seed;
  spec.rough.rms_m = 0.001;
  spec.rough.correlation_length_m = 0.015;
  return spec;
}

SurfaceMesh roundTrip(const PatchSpec& spec, const std::string& name) {
  const test::ScopedTempDir dir(name);
  const std::string path = dir.path + "/patch.ply";
  writeMesh(path, generateWallPatch(spec).mesh);
  return readMesh(path);
}

/// Depth of `with` below `without` at distance s from (x, y) along the unit vector n.
struct Section {
  const SurfaceSampler& with;
  const SurfaceSampler& without;
  Eigen::Vector2d centre;
  Eigen::Vector2d across;
  double depthAt(double s) const {
    const Eigen::Vector2d p = centre + s * across;
    const auto a = with.height(p.x(), p.y());
    const auto b = without.height(p.x(), p.y());
    EXPECT_TRUE(a && b) << "no surface at " << p.transpose();
    return (a && b) ? *b - *a : 0.0;
  }
  /// Width of the region where the depth exceeds `threshold`, sampled every step (so it
  /// is the true width less up to 2 steps).
  double widthAbove(double threshold, double half_range, double step) const {
    double lo = 1e9, hi = -1e9;
    const int samples = static_cast<int>(2.0 * half_range / step);
    for (int k = 0; k <= samples; ++k)
      if (const double s = -half_range + k * step; depthAt(s) > threshold) {
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
    return hi - lo;
  }
};

Eigen::Vector2d unit(double angle_deg) {
  const double a = angle_deg * M_PI / 180.0;
  return {std::cos(a), std::sin(a)};
}

struct CrackCase {
  Profile profile;
  double angle_deg;
};

class SurfaceStraightCrack : public ::testing::TestWithParam<CrackCase> {};

TEST_P(SurfaceStraightCrack, HasTheAskedWidthAndDepthInTheReimportedMesh) {
  const CrackCase c = GetParam();
  PatchSpec plain = smallRoughSpec(7);
  PatchSpec cracked = plain;
  LinearFeature crack;
  // Off the grid lines and at an angle, so the vertex lines must be inserted.
  crack.x_m = 0.2513;
  crack.y_m = 0.2371;
  crack.angle_deg = c.angle_deg;
  crack.width_m = 0.006;
  crack.depth_m = 0.02;
  crack.profile = c.profile;
  cracked.cracks.push_back(crack);
  const SurfaceMesh with_mesh = roundTrip(cracked, "crack_with");
  const SurfaceMesh without_mesh = roundTrip(plain, "crack_without");
  const SurfaceSampler with(with_mesh), without(without_mesh);

  const double run = std::min(cracked.wall_run_m, crack.width_m / 10.0);
  for (double along : {-0.15, -0.031, 0.0, 0.077, 0.2}) {
    const Eigen::Vector2d dir = unit(crack.angle_deg);
    const Eigen::Vector2d n(-dir.y(), dir.x());
    const Section section{with, without, Eigen::Vector2d(crack.x_m, crack.y_m) + along * dir, n};
    EXPECT_NEAR(section.depthAt(0.0), crack.depth_m, kHeightTolM);
    // Outside the crack the surface is untouched.
    EXPECT_NEAR(section.depthAt(0.5 * crack.width_m + 1e-5), 0.0, kHeightTolM);
    EXPECT_NEAR(section.depthAt(-0.5 * crack.width_m - 1e-5), 0.0, kHeightTolM);
    const double step = 2e-5;
    EXPECT_NEAR(section.widthAbove(kHeightTolM, 0.01, step), crack.width_m, 2 * step + 1e-7) << "along " << along;
    switch (c.profile) {
      case Profile::kRect:
        EXPECT_NEAR(section.depthAt(0.5 * crack.width_m - run), crack.depth_m, kHeightTolM);
        EXPECT_NEAR(section.depthAt(-0.5 * crack.width_m + run), crack.depth_m, kHeightTolM);
        EXPECT_NEAR(section.depthAt(0.5 * crack.width_m - 0.5 * run), 0.5 * crack.depth_m, kHeightTolM);
        break;
      case Profile::kV:
        EXPECT_NEAR(section.depthAt(0.25 * crack.width_m), 0.5 * crack.depth_m, kHeightTolM);
        EXPECT_NEAR(section.depthAt(-0.1 * crack.width_m), 0.8 * crack.depth_m, kHeightTolM);
        break;
      case Profile::kU:
        EXPECT_NEAR(section.depthAt(0.25 * crack.width_m), std::sqrt(0.75) * crack.depth_m, kHeightTolM);
        break;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Profiles, SurfaceStraightCrack,
                         ::testing::Values(CrackCase{Profile::kRect, 0.0}, CrackCase{Profile::kRect, 33.0},
                                           CrackCase{Profile::kV, 0.0}, CrackCase{Profile::kV, 121.0},
                                           CrackCase{Profile::kU, 71.0}));

TEST(SurfaceHoles, HaveTheirDiameterAndDepth) {
  PatchSpec plain = smallRoughSpec(3);
  PatchSpec holed = plain;
  holed.holes.push_back(Hole{0.1537, 0.1811, 0.05, 0.03});
  holed.holes.push_back(Hole{0.35, 0.33, 0.012, 0.06});
  const SurfaceMesh with_mesh = roundTrip(holed, "holes_with");
  const SurfaceMesh without_mesh = roundTrip(plain, "holes_without");
  const SurfaceSampler with(with_mesh), without(without_mesh);
  for (const Hole& h : holed.holes) {
    for (double angle : {0.0, 90.0, 45.0, 17.0}) {
      const Section section{with, without, {h.x_m, h.y_m}, unit(angle)};
      EXPECT_NEAR(section.depthAt(0.0), h.depth_m, kHeightTolM);
      const double run = holed.wall_run_m;
      EXPECT_NEAR(section.depthAt(0.5 * h.diameter_m - run - 1e-6), h.depth_m, kHeightTolM);
      const double step = 2e-5;
      // The rim polygon touches the circle on the axes and lies at most run / 2 outside it.
      const double slack = (angle == 0.0 || angle == 90.0) ? 2 * step : run + 2 * step;
      const double width = section.widthAbove(kHeightTolM, h.diameter_m, step);
      EXPECT_GE(width, h.diameter_m - 2 * step - 1e-7) << "angle " << angle;
      EXPECT_LE(width, h.diameter_m + slack) << "angle " << angle;
    }
  }
}

TEST(SurfaceSteps, RaiseTheLeftSideByTheirHeight) {
  PatchSpec plain = smallRoughSpec(5);
  PatchSpec stepped = plain;
  stepped.steps.push_back(Step{0.25, 0.2, 30.0, 0.012});
  const SurfaceMesh with_mesh = roundTrip(stepped, "step_with");
  const SurfaceMesh without_mesh = roundTrip(plain, "step_without");
  const SurfaceSampler with(with_mesh), without(without_mesh);
  const Eigen::Vector2d dir = unit(30.0), left(-dir.y(), dir.x());
  for (double along : {-0.1, 0.0, 0.13}) {
    const Section section{with, without, Eigen::Vector2d(0.25, 0.2) + along * dir, left};
    EXPECT_NEAR(section.depthAt(0.5 * stepped.wall_run_m + 1e-6), -0.012, kHeightTolM);
    EXPECT_NEAR(section.depthAt(0.1), -0.012, kHeightTolM);
    EXPECT_NEAR(section.depthAt(-0.5 * stepped.wall_run_m - 1e-6), 0.0, kHeightTolM);
    EXPECT_NEAR(section.depthAt(0.0), -0.006, kHeightTolM);
  }
}

TEST(SurfaceCrackNetwork, EveryPolylineSegmentHasTheAskedDepth) {
  PatchSpec plain = smallRoughSpec(11);
  PatchSpec net = plain;
  net.network.count = 3;
  net.network.segments = 5;
  net.network.segment_length_m = 0.08;
  net.network.width_m = 0.004;
  net.network.depth_m = 0.01;
  net.network.profile = Profile::kV;
  const SurfaceMesh with_mesh = roundTrip(net, "network_with");
  const SurfaceMesh without_mesh = roundTrip(plain, "network_without");
  const SurfaceSampler with(with_mesh), without(without_mesh);
  int checked = 0;
  const SurfaceFeatures drawn(net, crackNetworkSeed(net.seed), net.grid_m);
  for (const auto& line : drawn.networkPolylines()) {
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Eigen::Vector2d mid = 0.5 * (line[k] + line[k + 1]);
      const Eigen::Vector2d dir = (line[k + 1] - line[k]).normalized();
      if ((line[k + 1] - line[k]).norm() < 3 * net.network.width_m) continue;
      const Section section{with, without, mid, Eigen::Vector2d(-dir.y(), dir.x())};
      // Another polyline may cross here and be deeper nowhere (same depth), so = holds.
      EXPECT_NEAR(section.depthAt(0.0), net.network.depth_m, kHeightTolM);
      EXPECT_NEAR(section.depthAt(0.25 * net.network.width_m), 0.5 * net.network.depth_m, kHeightTolM + 1e-9)
          << "segment " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5);
}

/// Every edge of the structured face is used once in each direction (interior) or once
/// (rim): no T-junctions, no overlaps; the projected triangles tile the face.
void expectConforming(const PatchSpec& spec) {
  const WallPatch patch = generateWallPatch(spec);
  const auto& v = patch.mesh.vertices_m;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  double projected_area = 0.0;
  int flipped = 0;
  for (std::size_t t = 0; t < patch.face_triangles; ++t) {
    const auto& tri = patch.mesh.triangles[t];
    const Eigen::Vector2d a = v[tri[0]].head<2>().cast<double>(), b = v[tri[1]].head<2>().cast<double>(),
                          c = v[tri[2]].head<2>().cast<double>();
    const double area = 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
    flipped += area <= 0.0;
    projected_area += area;
    for (int k = 0; k < 3; ++k) ++directed[{tri[k], tri[(k + 1) % 3]}];
  }
  EXPECT_EQ(flipped, 0) << "flipped or degenerate triangles";
  EXPECT_NEAR(projected_area, spec.size_m * spec.size_m, 1e-6);
  int rim_edges = 0, doubled = 0, open_inside = 0;
  const float size = static_cast<float>(spec.size_m);
  for (const auto& [edge, count] : directed) {
    doubled += count != 1;
    if (!directed.count({edge.second, edge.first})) {
      ++rim_edges;
      const Eigen::Vector3f a = v[edge.first], b = v[edge.second];
      const bool on_rim = (a.x() == 0.0f && b.x() == 0.0f) || (a.y() == 0.0f && b.y() == 0.0f) ||
                          (a.x() == size && b.x() == size) || (a.y() == size && b.y() == size);
      open_inside += !on_rim;
    }
  }
  EXPECT_EQ(doubled, 0);
  EXPECT_EQ(open_inside, 0) << "open edges inside the face (T-junctions)";
  EXPECT_GE(rim_edges, 4 * patch.grid_cells);
}

TEST(SurfaceFaceMesh, StaysConformingAndCoversTheFaceOnce) {
  PatchSpec spec = smallRoughSpec(2);
  spec.cracks.push_back(LinearFeature{0.2, 0.21, 12.0, 0.008, 0.02, 0.0, Profile::kRect});
  spec.grooves.push_back(LinearFeature{0.2, 0.21, 95.0, 0.03, 0.02, 0.2, Profile::kU});
  spec.holes.push_back(Hole{0.2, 0.21, 0.04, 0.03});
  spec.steps.push_back(Step{0.3, 0.3, -60.0, 0.01});
  spec.network.count = 4;
  expectConforming(spec);
}

TEST(SurfaceFaceMesh, StaysConformingWhenCutsRunAlongGridLinesAndThroughVertices) {
  PatchSpec spec = smallRoughSpec(8);
  // On a 5 mm grid: along a grid line, along the diagonals through vertices, a hole centred
  // on a vertex, a step on a grid line, a finite crack ending on a vertex.
  spec.cracks.push_back(LinearFeature{0.25, 0.25, 0.0, 0.01, 0.02, 0.0, Profile::kV});
  spec.cracks.push_back(LinearFeature{0.25, 0.25, 45.0, 0.02, 0.02, 0.0, Profile::kRect});
  spec.cracks.push_back(LinearFeature{0.1, 0.4, 90.0, 0.005, 0.01, 0.1, Profile::kV});
  spec.grooves.push_back(LinearFeature{0.25, 0.25, 135.0, 0.04, 0.01, 0.0, Profile::kU});
  spec.holes.push_back(Hole{0.35, 0.1, 0.05, 0.03});
  spec.steps.push_back(Step{0.1, 0.1, 90.0, 0.01});
  expectConforming(spec);
}

/// Volume enclosed by outward triangles (divergence theorem), about a point near the centre.
double enclosedVolume(const SurfaceMesh& mesh, const Eigen::Vector3d& centre) {
  double volume = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices_m[tri[0]].cast<double>() - centre,
                          b = mesh.vertices_m[tri[1]].cast<double>() - centre,
                          c = mesh.vertices_m[tri[2]].cast<double>() - centre;
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

TEST(SurfaceCube, IsClosedAndHoldsTheHolesVolume) {
  PatchSpec plain = smallRoughSpec(4);
  PatchSpec holed = plain;
  holed.holes.push_back(Hole{0.25, 0.25, 0.05, 0.03});
  const Eigen::Vector3d centre(0.25, 0.25, -0.25);
  const double v_plain = enclosedVolume(generateWallPatch(plain).mesh, centre);
  const double v_holed = enclosedVolume(generateWallPatch(holed).mesh, centre);
  // Closed and outward: size^3 plus the face's mean height (0 within 0.1 mm) times size^2.
  EXPECT_NEAR(v_plain, std::pow(plain.size_m, 3), 1e-4 * plain.size_m * plain.size_m);
  // The hole removes pi r^2 depth, less half its wall ring (wall run 0.2 mm: 0.8 %).
  const double r = 0.025, depth = 0.03;
  EXPECT_NEAR(v_plain - v_holed, M_PI * r * r * depth, 0.015 * M_PI * r * r * depth);
}

}  // namespace
}  // namespace climbsim::surface
