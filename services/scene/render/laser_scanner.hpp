#pragma once
/// @file
/// The 2D laser scanner (docs/design.md#models, idl/scene.idl LaserScan): beams in the x-y plane of
/// the scanner frame S, counter-clockwise about z_S, beam i at angle
/// angle_min + i * angle_increment from x_S. A beam's range is the distance from the origin of
/// S to the first surface it meets (excluded parts do not count); +inf when nothing lies
/// within [range_min, range_max].

#include <vector>

#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// Largest number of beams of one scan (idl/scene.idl).
constexpr int kMaxLaserBeams = 4096;

/// Defaults: 240° field of view in 682 beams 0.352423° (= 240°/681) apart, starting at -120°,
/// 4 m range (the scene XML's distance_sensor, docs/scene-files.md#scene-xml).
struct LaserParams {
  double angle_min_rad = -120.0 * 3.14159265358979323846 / 180.0;  ///< angle of beam 0 from x_S [rad]
  double angle_increment_rad = 240.0 / 681.0 * 3.14159265358979323846 / 180.0;  ///< > 0 [rad]
  int beam_count = 682;        ///< 1..4096
  double range_min_m = 0.0;    ///< hits nearer than this are ignored [m], >= 0
  double range_max_m = 4.0;    ///< hits farther than this are misses [m], > range_min_m

  /// A symmetric scan about x_S as the scene XML gives it: beams from -range/2 to +range/2,
  /// count = 1 + floor(range / resolution + 0.01) (so a resolution rounded to a few digits,
  /// like 0.352423 for 240/681, still gives the beam on +range/2).
  static LaserParams fromScanRange(double scan_angle_range_deg, double angular_resolution_deg, double max_distance_m);

  /// Throws climbsim::ConfigError naming the field and value when a value is out of range.
  void validate() const;
  /// Angle of beam i [rad].
  double beamAngle_rad(int i) const { return angle_min_rad + i * angle_increment_rad; }
};

/// One sweep.
struct LaserScan {
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double range_min_m = 0.0;
  double range_max_m = 0.0;
  Pose T_W_S = Pose::Identity();  ///< where the scan was taken
  std::vector<float> ranges_m;             ///< one per beam [m]; +inf = nothing in range
};

}  // namespace climbsim::scene
