#pragma once
/// @file
/// Parameters of the airflow model (docs/design.md#airflow-and-downforce): volumes, sealing
/// segments, valves, suction engines, gas constants and the numerics. Plain values in SI units; the
/// robot geometry fills them (a later step), the model never reads files.

#include <array>
#include <cstdint>
#include <vector>

#include "climbsim/robot/robot_description.hpp"
#include "ode_system.hpp"

namespace climbsim::thermo {

/// Volume indices: chambers 1..N are 0..N-1, the reservoir (where the robot has one) is N
/// (ThermoParams::reservoir()); these are the pressure states. The ambient (fixed pressure,
/// not a state) is kAmbient.
constexpr int kAmbient = -1;

/// Most chambers, engines, sealing segments (climbsim/robot/robot_description.hpp) and
/// pressure states.
using climbsim::kMaxChambers;
using climbsim::kMaxEngines;
using climbsim::kMaxSegments;
constexpr int kMaxVolumes = kMaxChambers + 1;
static_assert(kMaxVolumes + 2 <= kMaxOdeSize, "the pressures and the two mass counters fit the ODE");

/// Gas and ambient. Defaults are docs/design.md#airflow-and-downforce.
struct GasParams {
  double ambient_pressure_pa = 100000.0;  ///< p_o, > 0
  double kappa = 1.402;                   ///< isentropic exponent in dp/dt = -(kappa R T / V) sum mdot, > 0
  double gas_constant_jpkgk = 287.058;    ///< specific gas constant of air R, > 0
  double temperature_k = 293.15;          ///< T, > 0
  double orifice_density_kgpm3 = 1.1883;  ///< rho of the orifice law (constant), > 0
};

/// One sealing segment: an orifice between two volumes whose leak area is an input.
/// Positive mass flow goes from volume_a to volume_b.
struct SealingSegment {
  int volume_a = 0;  ///< a volume index (0..N-1 chamber, N reservoir) or kAmbient
  int volume_b = 0;  ///< likewise, != volume_a; at most one of the two is the ambient
};

/// One suction engine on the reservoir or, without one, on a chamber: the volume it pumps,
/// p_v below. Fan curve at speed s (0..1), with the fan affinity laws (volume flow ~ s,
/// pressure rise ~ s^2):
///   dp_fan = dp_max s^2 (1 - Q / (Q_max s)),  i.e.  Q = Q_max s - Q_max dp_fan / (dp_max s),
/// solved at dp_fan = p_o - p_v; Q is the volume flow at the pumped volume's density
/// rho_v = p_v / (R T), so the mass flow removed from it is rho_v Q.
/// Q = 0 when dp_fan >= dp_max s^2 (the engine does not blow air back) and when s = 0.
struct SuctionEngineParams {
  double pressure_rise_max_pa = 0.0;   ///< dp_max at zero flow and full speed, > 0
  double volume_flow_max_m3ps = 0.0;   ///< Q_max at zero pressure rise and full speed, > 0
  double speed_lag_s = 0.0;            ///< tau of ds/dt = (s_cmd - s) / tau, > 0
  static constexpr int kPumpsReservoir = -1;
  /// The chamber it pumps (0..N-1), or kPumpsReservoir: the reservoir.
  int chamber = kPumpsReservoir;
};

/// The valves between the reservoir and each chamber 1..N (all alike; robots with a
/// reservoir only).
/// Effective area = opening * max_area_m2 * discharge_coefficient.
/// A command takes effect command_delay_s after the step that carried it (pure delay),
/// then the opening moves towards it at 1 / full_stroke_s per second (rate limit).
struct ValveParams {
  double max_area_m2 = 0.0;            ///< > 0
  double discharge_coefficient = 0.0;  ///< in (0, 1]
  double full_stroke_s = 0.0;          ///< time for opening 0 -> 1, > 0
  double command_delay_s = 0.0;        ///< >= 0; rounded to whole nanoseconds
};

/// Which integrator steps the ODE.
enum class IntegratorKind {
  /// default: L-stable Rosenbrock, order 2, monotone on decaying modes (docs/design.md#thermo-integrator)
  kRos2,
  kRodas3,         ///< L-stable Rosenbrock, order 3; overshoots slightly on stiff modes
  kDormandPrince,  ///< explicit 5(4), for comparison only
};

/// A plant fault (the scenario's `faults`): it acts in the plant, so that it holds whatever
/// controller commands (an external one too). It takes effect at the first step whose start
/// t_ns >= this->t_ns:
///  - kValveStuck (robots with valves): the valve of `chamber` targets `opening` from then on, at once (pending
///    delayed commands for it are discarded) and ignores every later command; the opening
///    still moves towards the target at the valve's rate 1 / full_stroke_s.
///  - kEngineFailure: engine `engine` is commanded off from then on whatever the inputs say;
///    its speed decays with the engine's lag.
struct PlantFault {
  enum class Kind { kValveStuck, kEngineFailure };
  Kind kind = Kind::kValveStuck;
  std::int64_t t_ns = 0;  ///< clock time it takes effect at [ns]
  int chamber = 0;        ///< kValveStuck: chamber 1..N
  double opening = 0.0;   ///< kValveStuck: the opening it sticks at, [0, 1]
  int engine = 0;         ///< kEngineFailure: engine 1..engines.size()
};

/// Everything the model needs, SI units. validate() before use (ThermoModel does).
struct ThermoParams {
  GasParams gas;
  /// V_1..V_N [m^3], each > 0; N = chamber_volume_m3.size() in 1..kMaxChambers sizes the model.
  std::vector<double> chamber_volume_m3;
  /// A reservoir R between the valves and the engines; without one there are no valves and
  /// each engine pumps its chamber (SuctionEngineParams::chamber).
  bool has_reservoir = true;
  double reservoir_volume_m3 = 0.0;         ///< V_R, > 0 with a reservoir (ignored without)
  /// Suction area A_i of chamber i (the wall area it pulls on) [m^2], > 0; N entries.
  std::vector<double> chamber_area_m2;
  /// Centroid P_i of chamber i's suction area in the robot frame (x, y) [m], finite; N entries.
  std::vector<std::array<double, 2>> p_RobotChamber_m;
  std::vector<SealingSegment> segments;     ///< leak paths; leak areas come with the inputs
  /// In parallel on the reservoir, or each on its chamber; at most kMaxEngines, may be empty.
  std::vector<SuctionEngineParams> engines;
  ValveParams valve;                        ///< with a reservoir (ignored without)
  /// Below this |dp| the orifice law is the laminar cubic blend (see orifice.hpp), > 0.
  double laminar_threshold_pa = 10.0;
  IntegratorKind integrator = IntegratorKind::kRos2;
  /// Tolerances in Pa (pressures only). ROS2 takes a step explicitly (Heun) where h times
  /// the stiffness bound is below 2 and continues from its Euler predictor where that is
  /// within 0.1 of the tolerance (ode_system.hpp; docs/design.md#thermo-integrator).
  StepControl step_control = [] {
    StepControl c;
    c.explicit_below = 2.0;
    c.euler_below = 0.1;
    return c;
  }();
  double initial_step_s = 1e-4;              ///< first step proposal of a fresh state, > 0
  /// Plant faults, in any order (ThermoState::fault_in_force keeps which have taken effect).
  std::vector<PlantFault> faults;

  /// Number of chambers N.
  int chamberCount() const { return static_cast<int>(chamber_volume_m3.size()); }
  /// Number of pressure states: N, plus 1 with a reservoir.
  int volumeCount() const { return chamberCount() + (has_reservoir ? 1 : 0); }
  /// The reservoir's volume index N (meaningful with a reservoir).
  int reservoir() const { return chamberCount(); }
  /// Number of valves: N with a reservoir, 0 without.
  int valveCount() const { return has_reservoir ? chamberCount() : 0; }
  /// The volume index engine e pumps: its chamber, or the reservoir.
  int engineVolume(std::size_t e) const {
    return engines[e].chamber == SuctionEngineParams::kPumpsReservoir ? reservoir() : engines[e].chamber;
  }

  /// Throws climbsim::ConfigError with one line naming the parameter and its value, e.g.
  /// "thermo: chamber_volume_m3[2] = -1 (must be finite and > 0)", for a chamber count
  /// outside 1..kMaxChambers, areas or centroids not one per chamber, more than kMaxEngines
  /// engines or kMaxSegments segments, non-positive or non-finite volumes, areas, gas constants, engine and valve
  /// values, a discharge coefficient above 1, a negative delay, segments joining a volume
  /// to itself, the ambient to itself or naming a volume the robot lacks, an engine on the
  /// reservoir of a robot without one or on a chamber it lacks, bad step-control values,
  /// and a fault naming a chamber outside 1..N (or a valve of a robot without valves), an
  /// engine the robot lacks or an opening outside [0, 1].
  void validate() const;

  /// The pure delay of valve commands in integer nanoseconds (llround of command_delay_s).
  std::int64_t valveDelayNs() const;
};

}  // namespace climbsim::thermo
