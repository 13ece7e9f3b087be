#pragma once
/// @file
/// The features of a patch as height functions of (x, y) in the patch frame and as the cut
/// segments that make their profile breakpoints mesh edges (face_mesh.hpp).
///
/// Height of the structured face: z = rough(x, y) + sum of step offsets - max of the
/// depressions (cracks, grooves, network cracks, holes), so where depressions overlap the
/// deeper one wins.

#include <vector>

#include <Eigen/Core>

#include "climbsim/wall_patches/face_mesh.hpp"
#include "climbsim/wall_patches/patch_spec.hpp"

namespace climbsim::surface {

/// Piecewise-linear profile: depth fraction (0..1) at distance s [m] from the feature's
/// centre (line, segment or point); s ascending, 0 beyond the last breakpoint.
struct ProfileBreakpoints {
  std::vector<double> s_m;
  std::vector<double> depth_fraction;
  double at(double s) const;
};

/// Breakpoints of a crack or groove profile of total width width_m (breakpoints at most
/// width / 4 apart, so the mesh has vertex lines that fine across the feature). A rect
/// profile's walls run over min(wall_run_m, width_m / 10).
ProfileBreakpoints linearProfile(Profile profile, double width_m, double wall_run_m);

/// A depression: depth_m times the profile at a distance s from its centre. Without
/// polygon_sides, s is the distance from the segment origin + t dir, t in
/// [t_begin, t_end] (infinite: a line). With polygon_sides = N > 0 (holes), s is the
/// polygon gauge max_k n_k.(p - origin) of the regular N-gon whose side normals n_k point at
/// angles 2 pi k / N: linear inside each sector, so holes are exact with chord and corner cuts.
struct Depression {
  CutSegment centre;
  double depth_m = 0.0;
  ProfileBreakpoints profile;
  int polygon_sides = 0;
  double distance(const Eigen::Vector2d& p_m) const;
};

/// A step: height_m times clamp((n.(p - origin) + run / 2) / run, 0, 1), n = dir turned +90 deg.
struct StepFeature {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d dir = Eigen::Vector2d::UnitX();
  double height_m = 0.0;
  double run_m = 0.0;
};

/// All features of one spec, with the crack network drawn from its seed.
class SurfaceFeatures {
 public:
  /// `network_seed` seeds the crack polylines; `grid_m` sets the number of hole chords.
  SurfaceFeatures(const PatchSpec& spec, std::uint64_t network_seed, double grid_m);

  /// Height offset of the features at (x, y) [m]: steps minus the deepest depression.
  double heightOffset(const Eigen::Vector2d& p_m) const;

  /// Every vertex line the mesh needs.
  const std::vector<CutSegment>& cuts() const { return cuts_; }
  const std::vector<Depression>& depressions() const { return depressions_; }
  /// The crack network's polylines (face coordinates), for reports and tests.
  const std::vector<std::vector<Eigen::Vector2d>>& networkPolylines() const { return polylines_; }

 private:
  void addLinear(const LinearFeature& feature, double wall_run_m);
  void addSegmentDepression(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double width_m,
                            double depth_m, Profile profile, double wall_run_m);
  void addHole(const Hole& hole, double wall_run_m, double grid_m);
  void addNetwork(const PatchSpec& spec, std::uint64_t seed);

  std::vector<Depression> depressions_;
  std::vector<StepFeature> steps_;
  std::vector<CutSegment> cuts_;
  std::vector<std::vector<Eigen::Vector2d>> polylines_;
};

}  // namespace climbsim::surface
