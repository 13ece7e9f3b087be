#pragma once
/// @file
/// The reference adhesion controller of a robot without a reservoir (docs/controllers.md#the-engine-law):
/// its engines pump their chambers directly and there are no valves, so the downforce F is held
/// at its set-point F* through the engines' speed. Pure C++: no DDS, no wall clock.
///
/// Notation: s_i = p_o - p_i the suction of chamber i [Pa], A_i its suction area [m²], P the
/// chambers an engine pumps (engines.chambers of the robot file), c_k the chamber of engine k,
/// omega_k its commanded speed in [0, 1], s_max the engines' suction at zero flow and full speed
/// (engines.dp_max_pa), dt the control period. Every step, in this order:
///
/// 1. Force of the chambers no engine pumps (they follow their neighbours):
///        F_u = sum_{i not in P} A_i max(0, s_i).
/// 2. Balance (when enabled; a pumped chamber whose centroid P_i lies off the centre, at r_i): a
///    trim b_i integrates how far the point of action P_F lies towards the chamber,
///        d b_i / dt = (P_F . P_i) / (r_i² balance_tau_s),   b_i in [-max_trim, max_trim];
///    held while every engine on the chamber runs at full speed and the trim would ask for more.
/// 3. Shares: the pumped chambers' suction targets, trimmed and together giving F*,
///        s*_i = min(s_F (1 - b_i), s_max),   s_F = max(0, F* - F_u) / sum_{i in P} A_i (1 - b_i),
///    so that sum_{i in P} A_i s*_i + F_u = F* while no target is capped.
/// 4. Engine speeds: a PI law on each engine's chamber error, normalised by s_max,
///        e_k = (s*_c - s_c) / s_max,   omega_ff,k = sqrt(s*_c / s_max)   (c = c_k),
///    in velocity form with the feed-forward's change,
///        omega_k += (omega_ff,k - omega_ff,k,prev) + K_P (e_k - e_k,prev) + dt e_k / tau_I,
///    clamped to [0, 1]: the speed integrates its own error and cannot wind up. omega_ff is the
///    speed whose fan curve (docs/design.md#airflow-and-downforce: zero-flow suction
///    s_max omega²) just reaches the target: a change of target (set-point, trims, F_u) moves
///    the speed at once; the integral finds what the leak needs on top. With K_P tau_I = tau_e
///    (the engines' speed lag, engines.speed_lag_s) the PI's zero cancels the lag's pole: the
///    chamber follows its target as a first-order lag of about tau_I / G, G = d(s/s_max)/d omega
///    the slope where fan curve and leak meet (2 omega without a leak; 0.62 on the
///    single-chamber robot at 700 N by an independent steady solve: about 0.5 s there). In
///    steady state e_k = 0: every pumped chamber holds its share and F = F*, unless an engine
///    runs at full speed (its chamber then short: a leak beyond the engine; F < F*).
/// The first step starts from the engines at rest (omega = 0, e_prev = 0, omega_ff,prev = 0):
/// the feed-forward and the proportional part then give the starting speed.

#include <array>
#include <cstdint>
#include <vector>

#include "adhesion_controller.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/model_contract.hpp"

namespace climbsim::controller {

/// The least tau_I [s] a robot gives the law: an engine that follows its command faster than this
/// is not followed faster (the integral's step dt / tau_I stays small at the exchange periods
/// scenarios use, 1-10 ms).
inline constexpr double kMinEngineIntegralS = 0.05;

/// Geometry, engines, set-point and gains of the engine law. Units in the names; every value finite.
struct EngineControllerParams {
  double ambient_pressure_pa = 100000.0;                 ///< p_o, > 0
  std::vector<double> chamber_area_m2;                   ///< A_i, > 0, one per chamber (N)
  std::vector<std::array<double, 2>> p_RobotChamber_m;   ///< centroids P_i (x, y), one per chamber [m]
  std::vector<int> engine_chamber;                       ///< c_k: chamber index 0..N-1 of each engine
  double desired_downforce_n = 700.0;                    ///< F*, > 0
  bool balance = true;                                   ///< hold P_F at the centre
  double max_suction_pa = 15000.0;                       ///< s_max (engines.dp_max_pa), > 0
  double engine_integral_s = 0.3;                        ///< tau_I (engines.speed_lag_s), > 0
  double engine_prop = 1.0;                              ///< K_P, >= 0 (K_P tau_I = tau_e)
  double balance_tau_s = 1.0;                            ///< balance loop integral time, > 0
  double max_trim = 0.5;                                 ///< |b_i| limit, in [0, 1)
};

/// Params for a robot without a reservoir: areas and centroids from its geometry, c_k from
/// engines.chambers, F* from adhesion.desired_downforce_n, s_max from engines.dp_max_pa, tau_I
/// from engines.speed_lag_s (at least kMinEngineIntegralS), p_o from gas.ambient_pressure_pa. ConfigError for a robot with a
/// reservoir (its valves hold the downforce: adhesion_controller.hpp).
EngineControllerParams engineControllerParamsFromRobot(const RobotDescription& robot, const RobotGeometry& geometry);

/// Everything of the engine law that evolves from one period to the next.
struct EngineControllerState {
  double desired_downforce_n = 0.0;          ///< F* [N]
  std::vector<double> trim{};                ///< b_i, one per chamber
  std::vector<double> speed{};               ///< omega_k, the commanded speeds
  std::vector<double> last_error{};          ///< e_k of the last step
  std::vector<double> last_feedforward{};    ///< omega_ff,k of the last step
  std::vector<double> target_pa{};           ///< s*_i of the last step, one per chamber (0 unpumped) [Pa]
};

/// Outputs of one control period.
struct EngineControllerOutputs {
  std::vector<double> engine_speed{};  ///< omega_k, each in [0, 1]
};

/// The engine law as a model of the contract (climbsim/model_contract.hpp).
class EngineController {
 public:
  using Params = EngineControllerParams;
  using State = EngineControllerState;
  using Inputs = AdhesionMeasurement;  ///< pressure_pa: N chambers (no reservoir)
  using Outputs = EngineControllerOutputs;

  /// Validates params (ConfigError naming the field and value).
  explicit EngineController(EngineControllerParams params);

  /// Engines at rest, no trims.
  EngineControllerState initialState() const;

  /// One control period [t_ns, t_ns + dt_ns), dt_ns > 0. Deterministic; a non-finite measurement,
  /// a pressure count other than N or dt_ns <= 0 throws std::invalid_argument.
  EngineControllerOutputs step(EngineControllerState& state, const AdhesionMeasurement& m, std::int64_t t_ns,
                               std::int64_t dt_ns) const;

  const EngineControllerParams& params() const { return params_; }
  int chamberCount() const { return static_cast<int>(params_.chamber_area_m2.size()); }
  int engineCount() const { return static_cast<int>(params_.engine_chamber.size()); }

 private:
  EngineControllerParams params_;
  std::vector<bool> pumped_;  ///< chamber i has an engine
};

static_assert(is_model_v<EngineController>, "EngineController keeps the model contract");

}  // namespace climbsim::controller
