#pragma once
/// @file
/// The airflow ODE of docs/design.md#airflow-and-downforce as an OdeSystem over one integration
/// interval.

#include <array>
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
struct ActuatorRamp {
  std::array<double, kNumChambers> valve_opening0{};
  std::array<double, kNumChambers> valve_rate_per_s{};
  std::array<double, kNumChambers> valve_target{};
  std::array<double, kNumChambers> valve_reach_s{};  ///< local time the valve lands on its target
  const double* engine_speed0 = nullptr;         ///< one per engine of the params
  const double* engine_speed_command = nullptr;  ///< one per engine of the params
  double engine_t0_s = 0.0;
};

/// Per-connection mass flows at one instant.
struct ConnectionFlows {
  std::vector<double> segment_kgps;                 ///< positive from volume_a to volume_b
  std::array<double, kNumChambers> valve_kgps{};    ///< positive from chamber to reservoir
  std::vector<double> engine_kgps;                  ///< out of the reservoir, >= 0
};

/// What one evaluation of AirflowSystem computes besides f: nothing, the stiffness bound,
/// or the Jacobian and ∂f/∂t.
enum class AirflowPass { kFlow, kStiffness, kJacobian };

/// y = (p_1..p_7, p_R [Pa], ambient inflow [kg], engine outflow [kg]);
///   dp_i/dt = -(kappa R T / V_i) sum_k mdot_ik      (mdot_ik from i to k; orifice.hpp)
///   d(ambient inflow)/dt = sum of segment flows out of the ambient
///   d(engine outflow)/dt = sum_e mdot_e              (suction_engine.hpp)
/// Valve c joins chamber c and the reservoir with area o_c(t) * max_area * Cd.
/// The referenced params, leak areas and ramp must outlive the system.
class AirflowSystem final : public OdeSystem {
 public:
  AirflowSystem(const ThermoParams& params, const std::vector<double>& leak_area_m2, const ActuatorRamp& ramp);

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

  const ThermoParams& params_;
  const std::vector<double>& leak_area_m2_;
  const ActuatorRamp& ramp_;
  std::array<double, kNumVolumes> dpdt_per_outflow_{};  // kappa R T / V_i
  double valve_area_scale_m2_ = 0.0;                     // max_area * Cd
  std::array<double, kNumVolumes + 1> sqrt_dpdt_per_outflow_{};  // sqrt(kappa R T / V_i), 0 for the ambient
  OrificeLaw law_;
  // The last exp(-(t0 + t) / lag): a step's end and the next step's start share it.
  mutable double decay_t_s_ = -1.0;
  mutable double decay_lag_s_ = 0.0;
  mutable double decay_ = 1.0;
};

}  // namespace climbsim::thermo
