#pragma once
/// @file
/// The robot description (deploy/robots/*.yaml): the parameters every service shares.
/// Plain values in SI units; the geometry derived from them is in robot_geometry.hpp.
///
/// Robot frame R: origin at the body centre in the sealing plane, z normal to the wall and
/// pointing away from it, x through the middle of chamber 1; angles counter-clockwise about z.

#include <string>
#include <vector>

namespace climbsim {

/// Every value of a robots/*.yaml file (docs/robot-files.md#default-values). The YAML keys are the
/// dotted member paths (`chambers.outer_volume_m3`), except where a member says otherwise.
struct RobotDescription {
  struct Body {
    double diameter_m = 0.0;         ///< outer diameter of the body, > 0
    /// Diameter of the outer sealing strip's centre line: the outer boundary of the ring
    /// chambers 1..N, whose outer radius is therefore sealed_diameter_m / 2.
    double sealed_diameter_m = 0.0;
    double mass_kg = 0.0;            ///< total mass, > 0
    double com_height_m = 0.0;       ///< centre of mass above the wall (along z), > 0
  };
  struct Chambers {
    /// Radius of the inner sealing strip's centre line: the centre chamber is the disc
    /// inside it, the ring chambers lie between it and sealed_diameter_m / 2.
    double centre_radius_m = 0.0;
    int outer_count = 0;             ///< N equal ring sectors, chamber 1 centred on +x; 3..36
    double outer_volume_m3 = 0.0;    ///< air volume of each ring chamber, > 0
    double centre_volume_m3 = 0.0;   ///< air volume of the centre chamber N+1, > 0
  };
  struct Reservoir {
    double volume_m3 = 0.0;          ///< vacuum reservoir R, > 0
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
  /// Identical suction engines in parallel on the reservoir, each with the linear fan curve
  /// dp = dp_max_pa * (1 - Q / flow_max_m3ps) at full speed.
  struct Engines {
    int count = 0;                   ///< 1..16
    double dp_max_pa = 0.0;          ///< pressure rise at zero flow, > 0
    double flow_max_m3ps = 0.0;      ///< volume flow at zero pressure rise, > 0
    double speed_lag_s = 0.0;        ///< first-order time constant of the engine speed, > 0
  };
  /// One valve between the reservoir and each chamber.
  struct Valves {
    double max_area_m2 = 0.0;             ///< geometric area when fully open, > 0
    double discharge_coefficient = 0.0;   ///< effective area = coefficient * area; (0, 1]
    double full_stroke_s = 0.0;           ///< closed to open at the rate limit, > 0
    double command_delay_s = 0.0;         ///< dead time of a command, >= 0
  };
  struct Wheels {
    /// Numbers (1..N, distinct) of the ring chambers holding a wheel; one wheel each, at the
    /// chamber's centre angle. The wheel count is the length of this list.
    std::vector<int> chambers;
    double mount_radius_m = 0.0;          ///< distance of each wheel contact from the centre
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
  Valves valves;
  Wheels wheels;
  Drive drive;
  Adhesion adhesion;
  Gas gas;
};

/// Reads and validates a robot description. Unknown, missing, duplicate or malformed keys and
/// every value outside its range or inconsistent with the others (see validateRobotDescription)
/// throw ConfigError with one line "<path>:<line>: <dotted.key> = <value>: <why>".
RobotDescription loadRobotDescription(const std::string& path);

/// Checks every value's range and the geometric relations between values: the strips fit on
/// the body (sealed_diameter_m / 2 + strip_width_m / 2 <= diameter_m / 2), the inner and outer
/// strips and neighbouring radial strips do not overlap, each wheel sits in a ring chamber clear
/// of its strips, the desired downforce is reachable. Throws ConfigError
/// "<source>: <dotted.key> = <value>: <why>" for the first violation.
void validateRobotDescription(const RobotDescription& description, const std::string& source);

}  // namespace climbsim
