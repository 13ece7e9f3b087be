#pragma once
/// @file
/// The robot geometry derived once from a RobotDescription: chambers (outlines, suction
/// areas, centroids, volumes), sealing segments (which volumes they join, lengths, centre
/// lines) and wheel positions. All points are in the robot frame R of robot_description.hpp,
/// in the sealing plane (z = 0).
///
/// Where the sealing strips lie: every strip's centre line is a chamber boundary. The outer
/// arcs lie at r2 = body.sealed_diameter_m / 2, the inner arcs at r1 = chambers.centre_radius_m,
/// the radial walls on the rays between neighbouring sectors from r1 to r2. Suction areas are
/// bounded by these centre lines: across a strip the pressure falls from one side's value to
/// the other's, so on average each side carries half of the strip's width.

#include <cstddef>
#include <string>
#include <vector>

#include "climbsim/robot/robot_description.hpp"

namespace climbsim {

/// Index of an air volume: 0..N-1 are the ring chambers 1..N, N is the centre chamber N+1,
/// N+1 is the reservoir R (N = chambers.outer_count; 6 for the default robot, so the ids are
/// 0..5 = chambers 1..6, 6 = centre chamber 7, 7 = R). The ambient is kAmbient.
using VolumeId = int;

/// The ambient air (pressure gas.ambient_pressure_pa); not a state of the thermo model.
inline constexpr VolumeId kAmbient = -1;

/// Largest angle between two samples of an arc in outlines and centre lines (1 degree): the
/// chord error is r (1 - cos 0.5°) < 14 µm at r = 0.36 m, far below a depth pixel (3 mm).
inline constexpr double kArcSampleStepRad = 3.14159265358979323846 / 180.0;

struct RobotGeometry {
  /// A point in the sealing plane, robot frame R.
  struct Point {
    double x_m = 0.0;
    double y_m = 0.0;
  };

  struct Chamber {
    VolumeId id = 0;
    int number = 0;                  ///< 1..N+1 (N+1 = centre)
    double volume_m3 = 0.0;          ///< air volume
    double inner_radius_m = 0.0;     ///< r1 for a ring sector, 0 for the centre disc
    double outer_radius_m = 0.0;     ///< r2 for a ring sector, r1 for the centre disc
    double centre_angle_rad = 0.0;   ///< bisector of a ring sector, (number - 1) * 2π/N; 0 for the centre
    double span_rad = 0.0;           ///< opening angle: 2π/N for a sector, 2π for the centre disc
    /// Suction area A_i: span/2 (outer² - inner²), i.e. θ/2 (r2² - r1²) or π r1².
    double area_m2 = 0.0;
    /// Centroid P_i of the suction area: on the bisector at
    /// r̄ = (2/3) (r2³ - r1³) / (r2² - r1²) * sin(θ/2) / (θ/2); the origin for the centre disc.
    Point p_RobotCentroid;
    /// Boundary polygon, counter-clockwise, not closed (last point != first); arcs sampled at
    /// most kArcSampleStepRad apart, so its area is A_i to within about 5e-5 relative.
    std::vector<Point> outline_Robot;
  };

  enum class SegmentKind { kOuter, kRadial, kInner };

  /// One sealing segment S_i of docs/design.md#sealing-and-leakage: a length of strip between two
  /// volumes.
  struct SealingSegment {
    std::string name;                ///< "outer<i>", "radial<i>_<i+1>" (cyclic: "radial6_1"), "inner<i>"
    SegmentKind kind = SegmentKind::kOuter;
    VolumeId volume_a = 0;           ///< the ring chamber i
    VolumeId volume_b = 0;           ///< kAmbient (outer), chamber i+1 (radial), the centre (inner)
    /// l_i: r2 θ (outer), r2 - r1 (radial), r1 θ (inner); the exact length, not the polyline's.
    double length_m = 0.0;
    /// Strip centre line from one end to the other (arcs counter-clockwise, radial walls
    /// outwards), arcs sampled at most kArcSampleStepRad apart.
    std::vector<Point> centreline_Robot;
  };

  struct Wheel {
    int chamber_number = 0;          ///< the ring chamber that holds the wheel
    double angle_rad = 0.0;          ///< that chamber's centre angle
    Point p_RobotWheel;              ///< wheel contact: wheels.mount_radius_m along angle_rad
  };

  int outer_count = 0;               ///< N
  double sector_angle_rad = 0.0;     ///< θ = 2π / N
  double centre_radius_m = 0.0;      ///< r1
  double ring_outer_radius_m = 0.0;  ///< r2 = body.sealed_diameter_m / 2
  double strip_width_m = 0.0;        ///< sealing.strip_width_m
  double reservoir_volume_m3 = 0.0;  ///< reservoir.volume_m3

  std::vector<Chamber> chambers;     ///< N + 1, indexed by VolumeId (ring chambers, then the centre)
  /// 3N segments: outer1..outerN, radial1_2..radialN_1, inner1..innerN, in this order.
  std::vector<SealingSegment> segments;
  std::vector<Wheel> wheels;         ///< in the order of wheels.chambers

  VolumeId centreChamber() const { return outer_count; }
  VolumeId reservoir() const { return outer_count + 1; }
  /// Number of volumes with a pressure state: the chambers and the reservoir (N + 2).
  int volumeCount() const { return outer_count + 2; }
  /// Air volume of a chamber or the reservoir (m³).
  double volumeOf(VolumeId id) const;
  /// "1".."N+1", "R", or "o" (ambient), as docs/design.md#airflow-and-downforce names them.
  std::string volumeName(VolumeId id) const;
  /// Indices into `segments` of the segments that touch volume `id`.
  std::vector<std::size_t> segmentsOf(VolumeId id) const;
  /// Total suction area sum A_i = π r2² (m²).
  double suctionArea() const;
};

/// Derives the geometry from a description (validated: call after loadRobotDescription or
/// validateRobotDescription). Nothing of it is stored in the robot file.
RobotGeometry computeGeometry(const RobotDescription& description);

/// The sealing segments' names in geometry order (the names Leakage, trace.csv's
/// leak_area_m2_<segment> columns and the thermo model's segments use).
std::vector<std::string> segmentNames(const RobotGeometry& geometry);

/// Leak areas of a flat wall, l_i * sealing.basic_gap_m per segment, in geometry order [m^2]
/// (docs/design.md#sealing-and-leakage with h_s = h_g): the leakage until the first Leakage sample
/// arrives.
std::vector<double> basicLeakAreas(const RobotDescription& description, const RobotGeometry& geometry);

}  // namespace climbsim
