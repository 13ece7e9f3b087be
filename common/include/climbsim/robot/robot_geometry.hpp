#pragma once
/// @file
/// The robot geometry derived once from a RobotDescription: chambers (outlines, suction
/// areas, centroids, volumes), sealing segments (which volumes they join, lengths, centre
/// lines) and wheels (kind, contact point). All points are in the robot frame R of
/// robot_description.hpp, in the sealing plane (z = 0).
///
/// Where the sealing strips lie: every strip's centre line is a chamber boundary. A boundary
/// between a chamber and the outside is an outer segment, a boundary between two chambers a
/// segment between those two. For a ring: outer arcs at r2 = chambers.sealed_diameter_m / 2,
/// inner arcs at r1 = chambers.centre_radius_m around the centre chamber, radial walls between
/// neighbouring sectors. Suction areas are bounded by these centre lines: across a strip the
/// pressure falls from one side's value to the other's, so on average each side carries half
/// of the strip's width.

#include <cstddef>
#include <string>
#include <vector>

#include "climbsim/robot/robot_description.hpp"

namespace climbsim {

/// Index of an air volume: 0..N-1 are the chambers 1..N (N = chamberCount(); for a ring with
/// a centre chamber the sectors come first and the centre is the last chamber), N is the
/// reservoir R where the robot has one. The default robot: 0..5 = chambers 1..6, 6 = centre
/// chamber 7, 7 = R. The ambient is kAmbient.
using VolumeId = int;

/// The ambient air (pressure gas.ambient_pressure_pa); not a state of the thermo model.
inline constexpr VolumeId kAmbient = -1;

/// Largest angle between two samples of an arc in outlines and centre lines (1 degree): the
/// chord error is r (1 - cos 0.5°) < 14 µm at r = 0.36 m, far below a depth pixel (3 mm).
inline constexpr double kArcSampleStepRad = 3.14159265358979323846 / 180.0;

struct RobotGeometry {
  /// A point in the sealing plane, robot frame R.
  using Point = RobotDescription::Point;

  struct Chamber {
    VolumeId id = 0;
    int number = 0;                  ///< 1..N
    double volume_m3 = 0.0;          ///< air volume
    /// Suction area A_i enclosed by the outline's strip centre lines [m^2]: exact for ring
    /// sectors (θ/2 (r2² - r1²)), discs (π r²) and polygons (shoelace formula).
    double area_m2 = 0.0;
    /// Centroid P_i of the suction area. A ring sector's lies on its bisector at
    /// r̄ = (2/3) (r2³ - r1³) / (r2² - r1²) * sin(θ/2) / (θ/2); a polygon's from the shoelace
    /// moments (1 / 6A) sum (x_k + x_k+1)(x_k y_k+1 - x_k+1 y_k).
    Point p_RobotCentroid;
    /// Boundary polygon, counter-clockwise, not closed (last point != first); arcs sampled at
    /// most kArcSampleStepRad apart, so its area is A_i to within about 5e-5 relative.
    std::vector<Point> outline_Robot;
    // Ring layout only (0 otherwise):
    double inner_radius_m = 0.0;     ///< r1 for a ring sector, 0 for the centre disc
    double outer_radius_m = 0.0;     ///< r2 for a ring sector, r1 for the centre disc
    double centre_angle_rad = 0.0;   ///< bisector of a ring sector, (number - 1) * 2π/N; 0 for the centre
    double span_rad = 0.0;           ///< opening angle: 2π/N for a sector, 2π for the centre disc
  };

  /// kOuter: chamber to ambient; kRadial: between neighbouring ring sectors; kInner: ring
  /// sector to the centre chamber; kWall: between two chambers of a grid or polygons layout.
  enum class SegmentKind { kOuter, kRadial, kInner, kWall };

  /// One sealing segment S_i of docs/design.md#sealing-and-leakage: a length of strip between two
  /// volumes.
  struct SealingSegment {
    /// Ring: "outer<i>", "radial<i>_<i+1>" (cyclic: "radial6_1"), "inner<i>"; other layouts:
    /// "outer<i>" (one per connected piece of chamber i's outer boundary: "outer<i>",
    /// "outer<i>b", ...), "wall<i>_<j>" (i < j).
    std::string name;
    SegmentKind kind = SegmentKind::kOuter;
    VolumeId volume_a = 0;           ///< a chamber
    VolumeId volume_b = 0;           ///< kAmbient (outer) or the chamber on the other side
    /// l_i: r2 θ (outer), r2 - r1 (radial), r1 θ (inner) for a ring, the exact length, not
    /// the polyline's; the polyline's length otherwise.
    double length_m = 0.0;
    /// Strip centre line from one end to the other (arcs counter-clockwise, radial walls
    /// outwards), arcs sampled at most kArcSampleStepRad apart.
    std::vector<Point> centreline_Robot;
  };

  struct Wheel {
    RobotDescription::WheelKind kind = RobotDescription::WheelKind::kSteerable;
    int chamber_number = 0;          ///< the ring chamber it is mounted in, or 0
    double angle_rad = 0.0;          ///< direction of the contact point from the origin
    Point p_RobotWheel;              ///< wheel contact point
    double radius_m = 0.0;           ///< wheel radius
    double friction_coefficient = 0.0;
  };

  RobotDescription::Layout layout = RobotDescription::Layout::kRing;
  int outer_count = 0;               ///< ring: number of sectors N; 0 for other layouts
  bool has_centre = false;           ///< ring: the centre chamber N+1 exists
  double sector_angle_rad = 0.0;     ///< ring: θ = 2π / N
  double centre_radius_m = 0.0;      ///< ring: r1 (0 without a centre chamber)
  double ring_outer_radius_m = 0.0;  ///< ring: r2 = chambers.sealed_diameter_m / 2
  double strip_width_m = 0.0;        ///< sealing.strip_width_m
  bool has_reservoir = false;        ///< reservoir section present
  double reservoir_volume_m3 = 0.0;  ///< reservoir.volume_m3 (0 without)

  std::vector<Chamber> chambers;     ///< indexed by VolumeId
  /// Ring: outer1..outerN, radial1_2..radialN_1, inner1..innerN, in this order. Other
  /// layouts: per chamber in number order its outer pieces, then the walls by (i, j).
  std::vector<SealingSegment> segments;
  std::vector<Wheel> wheels;         ///< in robot-file order
  /// The body's outline (circle sampled like an arc, or rectangle), counter-clockwise.
  std::vector<Point> body_outline_Robot;

  /// Number of chambers N.
  int chamberCount() const { return static_cast<int>(chambers.size()); }
  /// The ring's centre chamber (last chamber); only meaningful when has_centre.
  VolumeId centreChamber() const { return outer_count; }
  /// The reservoir's id, N; only meaningful when has_reservoir.
  VolumeId reservoir() const { return chamberCount(); }
  /// Number of volumes with a pressure state: the chambers and the reservoir if any.
  int volumeCount() const { return chamberCount() + (has_reservoir ? 1 : 0); }
  /// Air volume of a chamber or the reservoir (m³).
  double volumeOf(VolumeId id) const;
  /// "1".."N", "R", or "o" (ambient), as docs/design.md#airflow-and-downforce names them.
  std::string volumeName(VolumeId id) const;
  /// Indices into `segments` of the segments that touch volume `id`.
  std::vector<std::size_t> segmentsOf(VolumeId id) const;
  /// Total suction area sum A_i (m²).
  double suctionArea() const;
};

/// Derives the geometry from a description (validated: call after loadRobotDescription or
/// validateRobotDescription). Nothing of it is stored in the robot file.
RobotGeometry computeGeometry(const RobotDescription& description);

/// The chamber outlines of a description, before validation (validateRobotDescription checks
/// them): counter-clockwise, in chamber order.
std::vector<std::vector<RobotGeometry::Point>> chamberOutlines(const RobotDescription& description);

/// The sealing segments' names in geometry order (the names Leakage, trace.csv's
/// leak_area_m2_<segment> columns and the thermo model's segments use).
std::vector<std::string> segmentNames(const RobotGeometry& geometry);

/// Leak areas of a flat wall, l_i * sealing.basic_gap_m per segment, in geometry order [m^2]
/// (docs/design.md#sealing-and-leakage with h_s = h_g): the leakage until the first Leakage sample
/// arrives.
std::vector<double> basicLeakAreas(const RobotDescription& description, const RobotGeometry& geometry);

}  // namespace climbsim
