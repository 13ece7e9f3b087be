#pragma once
/// @file
/// The reference closed-loop adhesion controller (DESIGN.md §1.1): keeps the total downforce F
/// at its set-point and, optionally, the point of action P_F near the robot centre by commanding
/// the seven valves between the reservoir and the chambers. Pure C++: no DDS, no wall clock.
///
/// Structure (three loops, all with integral action and anti-windup):
///  - force loop: the common suction target s_base [Pa] (s = p_o - p, suction of a chamber)
///    starts at F* / sum_i A_i and integrates the force error,
///        d s_base / dt = (F* - F) / (sum_i A_i * force_tau_s),   s_base in [0, max_suction_pa];
///  - balance loop (ring chambers only, when enabled): a per-chamber trim b_i integrates how far
///    P_F lies towards chamber i,
///        d b_i / dt = (P_F . u_i) / (r_i * balance_tau_s),   b_i in [-max_trim, max_trim],
///    with u_i the unit vector towards the centroid P_i at distance r_i; the chamber's target is
///    s*_i = s_base (1 - b_i): a chamber on P_F's side pulls less, the opposite one more;
///  - valve loop: each valve's opening integrates its chamber's suction error,
///        d u_i / dt = valve_gain_per_pa_s * (min(s*_i, ratio * s_R) - s_i),   u_i in [0, 1],
///    a chamber never being asked for more than a fraction of the reservoir's suction s_R;
///    opening a valve lowers the chamber pressure towards the reservoir's.
/// The force loop holds while s_R <= s_base (the reservoir cannot deliver more), a trim holds
/// while its valve is fully open and the trim would ask for more: no loop winds up.

#include <array>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim::controller {

inline constexpr int kValveCount = 7;  ///< chambers 1..7, index i = chamber i + 1 (7 = centre)

/// Geometry, set-points and gains. Units in the names; every value finite.
struct AdhesionControllerParams {
  double ambient_pressure_pa = 100000.0;                 ///< p_o, > 0
  std::array<double, kValveCount> chamber_area_m2{};     ///< A_i, > 0
  std::array<std::array<double, 2>, kValveCount> p_RobotChamber_m{};  ///< centroids P_i (x, y)
  double desired_downforce_n = 2200.0;                   ///< F*, > 0
  bool balance = true;                                   ///< hold P_F at the centre
  double max_suction_pa = 22000.0;                       ///< upper limit of s_base, > 0
  double force_tau_s = 1.0;                              ///< force loop integral time, > 0
  double balance_tau_s = 1.0;                            ///< balance loop integral time, > 0
  double max_trim = 0.5;                                 ///< |b_i| limit, in [0, 1)
  double valve_gain_per_pa_s = 1e-4;                     ///< valve loop integral gain [1/(Pa s)], > 0
  /// A chamber's target is at most this fraction of the reservoir's suction, in (0, 1).
  double reservoir_tracking_ratio = 0.9;
};

/// Params for a robot: areas and centroids from its geometry, F* from adhesion.desired_downforce_n,
/// max suction from engines.dp_max_pa, p_o from gas.ambient_pressure_pa. Throws ConfigError when
/// the robot does not have 6 ring chambers (the valve command carries 7 openings).
AdhesionControllerParams adhesionControllerParamsFromRobot(const RobotDescription& robot,
                                                           const RobotGeometry& geometry);

/// What the controller measures at a step: ChamberState and AdhesionForce of the thermo service.
struct AdhesionMeasurement {
  std::array<double, 8> pressure_pa{};  ///< chambers 1..7, then the reservoir [Pa]
  double downforce_n = 0.0;             ///< F [N]
  std::array<double, 2> p_RobotPF_m{};  ///< P_F (x, y) in the robot frame [m]
};

class AdhesionController {
 public:
  /// Validates params (ConfigError naming the field and value).
  explicit AdhesionController(AdhesionControllerParams params);

  /// One control period of dt_s > 0 seconds: updates the loops with `m` and returns the valve
  /// openings to command, each in [0, 1]. Deterministic; a non-finite measurement throws
  /// std::invalid_argument and leaves the state unchanged.
  std::array<double, kValveCount> step(const AdhesionMeasurement& m, double dt_s);

  /// Changes F* (e.g. from the scenario) without resetting the loops; > 0.
  void setDesiredDownforce(double downforce_n);

  const AdhesionControllerParams& params() const { return params_; }
  double suctionTargetPa() const { return s_base_pa_; }   ///< s_base
  const std::array<double, kValveCount>& trim() const { return trim_; }          ///< b_i
  const std::array<double, kValveCount>& openings() const { return opening_; }   ///< u_i

 private:
  AdhesionControllerParams params_;
  double total_area_m2_ = 0.0;  ///< sum_i A_i
  double s_base_pa_ = 0.0;
  std::array<double, kValveCount> trim_{};
  std::array<double, kValveCount> opening_{};
};

}  // namespace climbsim::controller
