#pragma once
/// @file
/// The robot description (deploy/robots/*.yaml, docs/robot-files.md): the parameters every
/// service shares, for any vacuum-adhesion robot: a body, 1..kMaxChambers chambers laid out as a
/// ring, a grid, a single chamber or free polygons, sealing strips on their boundaries, a
/// reservoir with one valve per chamber or none (the engines then pump chambers directly),
/// engines, and 1..kMaxWheels wheels of three kinds. Plain values in SI units; the geometry
/// derived from them (outlines, areas, strips, wheel positions) is in robot_geometry.hpp.
///
/// Robot frame R: origin at the body centre in the sealing plane, z normal to the wall and
/// pointing away from it, x forwards (through the middle of chamber 1 for a ring); angles
/// counter-clockwise about z.

#include <string>
#include <vector>

namespace climbsim {

/// Most chambers a robot may have.
inline constexpr int kMaxChambers = 24;
/// Most wheels a robot may have.
inline constexpr int kMaxWheels = 8;
/// Most suction engines a robot may have.
inline constexpr int kMaxEngines = 16;
/// Most sealing segments a robot's chambers may make (idl/sealing.idl, idl/thermo.idl).
inline constexpr int kMaxSegments = 96;

/// Every value of a robots/*.yaml file (docs/robot-files.md). The YAML keys are the dotted
/// member paths (`chambers.volume_m3`), except where a member says otherwise.
struct RobotDescription {
  /// A point in the sealing plane, robot frame R [m].
  struct Point {
    double x_m = 0.0;
    double y_m = 0.0;
  };
  /// Outline of the body and of the single chamber.
  enum class Shape { kCircle, kRectangle };

  struct Body {
    Shape shape = Shape::kCircle;    ///< YAML `circle` or `rectangle`
    double diameter_m = 0.0;         ///< circle: outer diameter, > 0
    double length_m = 0.0;           ///< rectangle: extent along x, > 0
    double width_m = 0.0;            ///< rectangle: extent along y, > 0
    double mass_kg = 0.0;            ///< total mass, > 0
    double com_height_m = 0.0;       ///< centre of mass above the wall (along z), > 0
    /// Radius of the smallest circle about the origin that holds the body [m]: the
    /// radius for a circle, the half diagonal for a rectangle.
    double outerRadius() const;
  };

  /// How the chambers are laid out (YAML chambers.layout).
  enum class Layout {
    /// `ring`: `count` equal sectors between the centre disc (radius centre_radius_m; no
    /// centre chamber if 0 or absent: the sectors then meet at the origin) and
    /// sealed_diameter_m / 2, chamber 1 centred on +x, numbered counter-clockwise; the
    /// centre chamber is number count + 1.
    kRing,
    /// `grid`: rows x columns equal rectangles covering length_m (x) by width_m (y),
    /// centred on the origin; chamber 1 at the (-x, -y) corner, numbered along x first.
    kGrid,
    /// `single`: one chamber of `shape` (circle of diameter_m, or rectangle length_m by
    /// width_m) centred on the origin.
    kSingle,
    /// `polygons`: each chamber its own outline (`chambers.polygons`); neighbours share
    /// whole edges (the same two corner points).
    kPolygons,
  };

  /// One chamber of the `polygons` layout.
  struct PolygonChamber {
    std::vector<Point> outline;      ///< corners, either orientation, not closed; >= 3
    double volume_m3 = 0.0;          ///< air volume, > 0
  };

  struct Chambers {
    Layout layout = Layout::kRing;
    int count = 0;                   ///< ring: number of sectors, 1..kMaxChambers
    double sealed_diameter_m = 0.0;  ///< ring: diameter of the outer strip's centre line, > 0
    /// ring: radius of the inner strip's centre line; 0: no centre chamber.
    double centre_radius_m = 0.0;
    double centre_volume_m3 = 0.0;   ///< ring with a centre chamber: its air volume, > 0
    int rows = 0;                    ///< grid: cells along y, >= 1
    int columns = 0;                 ///< grid: cells along x, >= 1
    Shape shape = Shape::kCircle;    ///< single: its outline
    double diameter_m = 0.0;         ///< single circle: diameter of the strip's centre line
    double length_m = 0.0;           ///< grid or single rectangle: extent along x
    double width_m = 0.0;            ///< grid or single rectangle: extent along y
    /// Air volume of each ring sector, grid cell or the single chamber, > 0.
    double volume_m3 = 0.0;
    std::vector<PolygonChamber> polygons;  ///< polygons: the chambers 1..N in order
    /// Number of chambers the layout makes (ring: count + 1 with a centre chamber).
    int total() const;
  };

  /// Optional section: a vacuum reservoir R between the engines and the chambers' valves.
  struct Reservoir {
    bool present = false;            ///< the file has a `reservoir` section
    double volume_m3 = 0.0;          ///< > 0
  };
  struct Sealing {
    double strip_width_m = 0.0;      ///< width of every sealing strip, > 0
    double travel_m = 0.0;           ///< the strip extends and retracts up to ±travel_m, > 0
    /// Largest height difference between neighbouring sealing points per metre of distance
    /// (m/m), so that the adaptation does not depend on the camera resolution; > 0.
    double max_slope = 0.0;
    double basic_gap_m = 0.0;        ///< L_basic of docs/design.md#sealing-and-leakage, >= 0
    /// kappa_L of docs/design.md#sealing-and-leakage (dimensionless), >= 0
    double kappa_L = 0.0;
    /// Optional key (default false): bound each segment's leak by the channel cross-section
    /// along the strip's edge lines (services/sealing/model/channel_bound.hpp).
    bool channel_bound = false;
  };
  /// Identical suction engines, each with the linear fan curve
  /// dp = dp_max_pa * (1 - Q / flow_max_m3ps) at full speed: in parallel on the reservoir, or,
  /// without one, each on the chamber `chambers` names for it.
  struct Engines {
    int count = 0;                   ///< 1..kMaxEngines
    double dp_max_pa = 0.0;          ///< pressure rise at zero flow, > 0
    double flow_max_m3ps = 0.0;      ///< volume flow at zero pressure rise, > 0
    double speed_lag_s = 0.0;        ///< first-order time constant of the engine speed, > 0
    /// Without a reservoir (and only then): the chamber number (1..N) each engine pumps,
    /// one per engine; YAML key engines.chambers.
    std::vector<int> chambers;
  };
  /// One valve between the reservoir and each chamber; the section is required with a
  /// reservoir and refused without one.
  struct Valves {
    double max_area_m2 = 0.0;             ///< geometric area when fully open, > 0
    double discharge_coefficient = 0.0;   ///< effective area = coefficient * area; (0, 1]
    double full_stroke_s = 0.0;           ///< closed to open at the rate limit, > 0
    double command_delay_s = 0.0;         ///< dead time of a command, >= 0
  };
  /// What a wheel does (YAML wheels[i].kind).
  enum class WheelKind {
    kSteerable,  ///< `steerable`: steered about the wall normal and driven
    kFixed,      ///< `fixed`: driven, always rolling along x (differential or skid steering)
    kCaster,     ///< `caster`: passive, swivels freely and rolls freely
  };
  /// One wheel. Its contact point is either `chamber` + `mount_radius_m` (ring layout: on
  /// that ring chamber's centre angle, mount_radius_m from the origin) or `x_m`, `y_m`.
  struct Wheel {
    WheelKind kind = WheelKind::kSteerable;
    int chamber = 0;                      ///< ring chamber 1..count holding the wheel, or 0
    double mount_radius_m = 0.0;          ///< with `chamber`: distance from the origin, > 0
    double x_m = 0.0;                     ///< without `chamber`: contact point in R
    double y_m = 0.0;
    double radius_m = 0.0;                ///< wheel radius, > 0
    double friction_coefficient = 0.0;    ///< Coulomb friction wheel-wall, > 0
  };
  struct Drive {
    double max_speed_mps = 0.0;           ///< translational speed limit, > 0
    /// Steering rate limit, > 0. YAML key drive.max_steering_rate_degps (degrees per second).
    double max_steering_rate_radps = 0.0;
  };
  struct Adhesion {
    /// Set-point of the total downforce, > 0 and at most engines.dp_max_pa times the sealed
    /// area (more cannot be reached).
    double desired_downforce_n = 0.0;
  };
  /// Gas constants of docs/design.md#airflow-and-downforce.
  struct Gas {
    double ambient_pressure_pa = 0.0;     ///< p_o, > 0
    double temperature_k = 0.0;           ///< T, > 0
    double kappa = 0.0;                   ///< adiabatic exponent, (1, 5/3]
    double r_air_jpkgk = 0.0;             ///< specific gas constant R_air, > 0
    /// Density in the orifice law; within 10 % of p_o / (R_air T) (guards against typos).
    double rho_kgpm3 = 0.0;
  };

  std::string name;                  ///< non-empty; YAML key `name`
  Body body;
  Chambers chambers;
  Reservoir reservoir;
  Sealing sealing;
  Engines engines;
  Valves valves;                     ///< meaningful with a reservoir only
  std::vector<Wheel> wheels;         ///< 1..kMaxWheels, in file order
  Drive drive;
  Adhesion adhesion;
  Gas gas;
};

/// "circle" / "rectangle".
const char* toString(RobotDescription::Shape shape);
/// "ring" / "grid" / "single" / "polygons".
const char* toString(RobotDescription::Layout layout);
/// "steerable" / "fixed" / "caster".
const char* toString(RobotDescription::WheelKind kind);

/// Reads and validates a robot description. Unknown, missing, duplicate or malformed keys and
/// every value outside its range or inconsistent with the others (see validateRobotDescription)
/// are reported all at once: one ConfigError with one line "<path>:<line>: <key> = <value>:
/// <why>" per problem.
RobotDescription loadRobotDescription(const std::string& path);

/// Checks every value's range and the geometric relations between values: the chambers lie
/// inside the body and do not overlap, their outer strip closes into one loop, the wheels lie
/// inside the body clear of every strip, the counts are within their maxima, the engines and
/// valves fit the reservoir (or its absence), the desired downforce is reachable. Throws
/// ConfigError "<source>: <key> = <value>: <why>" listing every violation.
void validateRobotDescription(const RobotDescription& description, const std::string& source);

}  // namespace climbsim
