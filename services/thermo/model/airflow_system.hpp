#pragma once
/// @file
/// The airflow ODE of docs/design.md#airflow-and-downforce as an OdeSystem over one integration
/// interval.

#include <array>
#include <cstddef>
#include <vector>

#include "ode_system.hpp"
#include "orifice.hpp"
#include "thermo_params.hpp"

namespace climbsim::thermo {

/// How the actuators move over one integration interval, local time t [s] from its start:
///   valve opening  o_c(t) = o0_c + rate_c t until it reaches target_c, then target_c
///                  (rate_c = ±1/stroke towards the target, 0 at the target)
///   engine speed   s_e(t) = cmd_e + (s0_e - cmd_e) exp(-(t + engine_t0) / tau_e)
/// (engine_t0: the interval's start on the engines' own clock, so that several intervals
/// of an exchange period share one s0). ThermoModel::step ends every interval where a
/// valve lands, so that inside an interval the openings are linear in time.
/// Valve entries 0..ThermoParams::valveCount()-1 are used.
struct ActuatorRamp {
  std::array<double, kMaxChambers> valve_opening0{};
  std::array<double, kMaxChambers> valve_rate_per_s{};
  std::array<double, kMaxChambers> valve_target{};
  std::array<double, kMaxChambers> valve_reach_s{};  ///< local time the valve lands on its target
  const double* engine_speed0 = nullptr;         ///< one per engine of the params
  const double* engine_speed_command = nullptr;  ///< one per engine of the params
  double engine_t0_s = 0.0;
};

/// Per-connection mass flows at one instant.
struct ConnectionFlows {
  std::vector<double> segment_kgps;  ///< positive from volume_a to volume_b
  std::vector<double> valve_kgps;    ///< per valve, positive from chamber to reservoir
  std::vector<double> engine_kgps;   ///< out of the volume each engine pumps, >= 0
};

/// What one evaluation of AirflowSystem computes besides f: nothing, the stiffness bound,
/// or the Jacobian and ∂f/∂t.
enum class AirflowPass { kFlow, kStiffness, kJacobian };

/// What the airflow ODE derives from the params alone, made once per model (ThermoModel keeps
/// it; an AirflowSystem is made for every exchange period and refers to it).
struct AirflowLayout {
  /// Throws std::invalid_argument for more than kMaxSegments sealing segments.
  explicit AirflowLayout(const ThermoParams& params);

  int volumes;       ///< pressure states V
  int ambient_port;  ///< = V: the ambient's slot in the per-port arrays
  int valves;        ///< valves 0..valves-1, chamber c to the reservoir
  int reservoir;     ///< the reservoir's index (with valves)
  // Entries past the ports are never read: left uninitialised.
  std::array<double, kMaxVolumes> dpdt_per_outflow;           ///< kappa R T / V_i
  double valve_area_scale_m2 = 0.0;                           ///< max_area * Cd
  std::array<double, kMaxVolumes + 1> sqrt_dpdt_per_outflow;  ///< sqrt(kappa R T / V_i), 0 for the ambient
  /// The segments' ends as ports (the ambient is ambient_port); the first `segments` entries.
  std::size_t segments = 0;
  std::array<std::array<int, 2>, kMaxSegments> segment_ports;
  /// Engines grouped by the volume they pump, groups in order of first appearance: the flows
  /// of a group are summed before they enter its volume's balance. Group g's engines, in
  /// engine order, are engine_order[group_begin[g] .. group_begin[g + 1]).
  std::array<int, kMaxEngines> group_volume;  ///< per group
  std::array<int, kMaxEngines + 1> group_begin;
  std::array<int, kMaxEngines> engine_order;
  int groups = 0;
  OrificeLaw law;
};

/// y = (p_1..p_N, p_R if any [Pa], ambient inflow [kg], engine outflow [kg]);
///   dp_i/dt = -(kappa R T / V_i) sum_k mdot_ik      (mdot_ik from i to k; orifice.hpp;
///                                                    an engine's flow leaves the volume it pumps)
///   d(ambient inflow)/dt = sum of segment flows out of the ambient
///   d(engine outflow)/dt = sum_e mdot_e              (suction_engine.hpp)
/// Valve c (robots with a reservoir) joins chamber c and the reservoir with area
/// o_c(t) * max_area * Cd.
/// The referenced params, layout (made from the same params), leak areas and ramp must outlive
/// the system.
class AirflowSystem final : public OdeSystem {
 public:
  AirflowSystem(const ThermoParams& params, const AirflowLayout& layout, const std::vector<double>& leak_area_m2,
                const ActuatorRamp& ramp);

  void rhs(double t_s, const OdeVector& y, OdeVector& dydt) const override;
  void jacobian(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix& dfdy, OdeVector& dfdt) const override;
  /// f and a Gershgorin bound of the spectral radius of ∂f/∂p (see evaluate) from the
  /// slopes the orifice law and the fan curve give with the flows.
  double rhsWithStiffness(double t_s, const OdeVector& y, OdeVector& dydt) const override;
  /// The bound of rhsWithStiffness from the Jacobian: max_i sum_j |J_ij| sqrt(d_j / d_i).
  double stiffnessBound(const OdeMatrix& dfdy) const override;

  /// Call after changing the ramp the system refers to (a new piece of the period): drops
  /// what was cached for the old one.
  void rampChanged() const { decay_t_s_ = -1.0; }

  /// The flows of every connection at (t_s, y), for the outputs.
  void connectionFlows(double t_s, const OdeVector& y, ConnectionFlows& flows) const;

 private:
  // Returns the stiffness bound of rhsWithStiffness for AirflowPass::kStiffness, else 0.
  // kOutputs: also fill *flows (a compile-time switch: the inner loops stay branch-free).
  template <AirflowPass kPass, bool kOutputs = false>
  double evaluate(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix* dfdy, OdeVector* dfdt,
                  ConnectionFlows* flows) const;
  // evaluate for kVolumes pressure states (fixed_size.hpp; 0: the layout's count at run time).
  template <AirflowPass kPass, bool kOutputs, int kVolumes>
  double evaluateSized(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix* dfdy, OdeVector* dfdt,
                       ConnectionFlows* flows) const;

  // The bound of rhsWithStiffness from the summed weighted conductances of each port
  // (Balance in the .cpp; the engines' slopes are added here; an array of the ports) and
  // the engines' summed |slopes| per group.
  template <int kVolumes, class PortArray>
  double stiffnessOf(PortArray& weighted_conductance, const std::array<double, kMaxEngines>& engine_slope) const;
  // stiffnessBound for kVolumes pressure states.
  template <int kVolumes>
  double stiffnessBoundSized(const OdeMatrix& dfdy) const;

  const ThermoParams& params_;
  const AirflowLayout& layout_;
  const std::vector<double>& leak_area_m2_;
  const ActuatorRamp& ramp_;
  // The last exp(-(t0 + t) / lag): a step's end and the next step's start share it.
  mutable double decay_t_s_ = -1.0;
  mutable double decay_lag_s_ = 0.0;
  mutable double decay_ = 1.0;
};

}  // namespace climbsim::thermo
