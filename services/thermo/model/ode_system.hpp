#pragma once
/// @file
/// The ODE interface shared by the thermo integrators: a system dy/dt = f(t, y) of a size
/// fixed at construction, with its Jacobian, plus step-control settings and work counters.

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace climbsim::thermo {

/// Longest integrated state: the airflow's pressures (24 chambers and a reservoir) and two
/// cumulative mass counters (ambient inflow, engine outflow). The vectors and matrices
/// have their size at run time and this capacity at compile time, so that they live on
/// the stack whatever the robot.
constexpr int kMaxOdeSize = 27;

using OdeVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxOdeSize, 1>;
using OdeMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxOdeSize, kMaxOdeSize>;

/// dy/dt = f(t_s, y) for y of size() entries, with f independent of y[coupledSize()..]:
/// those entries are quadratures (running integrals such as the mass counters), which the
/// implicit integrator then need not put into its Newton matrix. t_s is local time [s]
/// from the start of the current integration interval, so that actuator trajectories need
/// no absolute time. The outputs of rhs and jacobian are resized to size() (no heap).
class OdeSystem {
 public:
  /// size in 1..kMaxOdeSize, coupled_size in 1..size (std::invalid_argument otherwise).
  OdeSystem(int size, int coupled_size);
  virtual ~OdeSystem() = default;
  /// Length of y.
  int size() const { return size_; }
  /// Number of leading entries of y that f depends on.
  int coupledSize() const { return coupled_size_; }
  /// dydt = f(t_s, y).
  virtual void rhs(double t_s, const OdeVector& y, OdeVector& dydt) const = 0;
  /// dydt = f, dfdy = ∂f/∂y and dfdt = ∂f/∂t at (t_s, y), in one pass because they
  /// share every flow evaluation. The Rosenbrock methods need ∂f/∂t because valve
  /// openings and engine speeds change within an interval.
  virtual void jacobian(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix& dfdy,
                        OdeVector& dfdt) const = 0;
  /// dydt = f(t_s, y); returns an upper bound of the spectral radius of the coupled block
  /// of ∂f/∂y [1/s]. The default takes the Gershgorin bound max_i sum_j |∂f_i/∂y_j| of
  /// jacobian(); systems that know their structure give it for the price of f.
  virtual double rhsWithStiffness(double t_s, const OdeVector& y, OdeVector& dydt) const;
  /// The same kind of bound from a Jacobian that jacobian() returned [1/s]; the default
  /// is Gershgorin's max_i sum_j |∂f_i/∂y_j| over the coupled block.
  virtual double stiffnessBound(const OdeMatrix& dfdy) const;

 private:
  int size_;
  int coupled_size_;
};

/// Step-size control of the adaptive integrators. The local error estimate err_i is
/// accepted when sqrt(mean_i (err_i / (abs_tol + rel_tol * |y_i|))^2) <= 1, taken over
/// the first `error_components` entries of y only, by default the coupled ones (the mass
/// counters are bookkeeping and must not steer the step size).
struct StepControl {
  double abs_tol = 1.0;          ///< absolute tolerance in the state's units [Pa], > 0
  double rel_tol = 0.0;          ///< relative tolerance, >= 0
  int error_components = 0;      ///< 0: OdeSystem::coupledSize(); else 1..OdeSystem::size()
  double min_step_s = 1e-12;     ///< below this the integration fails, > 0
  double max_step_s = 1.0;       ///< upper bound of a step [s], > min_step_s
  long max_steps = 1'000'000;    ///< per integrate() call, including rejected steps
  /// ROS2 only: a step of size h whose stiffness bound b (OdeSystem::rhsWithStiffness)
  /// gives h * b < explicit_below is taken with W = 0, i.e. as Heun's method (no Jacobian,
  /// no LU). In [0, 2]: Heun is stable and monotone on the real spectrum for h rho <= 2.
  /// 0 = every step implicit.
  double explicit_below = 0.0;
  /// ROS2 only: such an explicit step continues from its Euler predictor y + h f0 instead
  /// of Heun's result when its error norm is <= euler_below and h * b <= 1 (Euler then
  /// monotone), so that f at the predictor, evaluated anyway, is the next step's f.
  /// The local error of the continued solution is then ~ euler_below * tolerance.
  /// In [0, 1]; 0 = always Heun.
  double euler_below = 0.0;
};

/// Work done by an integrator; accumulated, never reset by the integrator.
struct IntegratorStats {
  long rhs_evals = 0;        ///< calls of OdeSystem::rhs
  long jacobian_evals = 0;   ///< calls of OdeSystem::jacobian (each also gives f; not counted in rhs_evals)
  long lu_decompositions = 0;
  long accepted_steps = 0;
  long rejected_steps = 0;
  long explicit_steps = 0;   ///< accepted or rejected ROS2 steps taken with W = 0 (explicit_below)
};

/// How many leading entries of y StepControl::error_components weighs for `system`.
/// Throws std::invalid_argument when it names more entries than the system has.
int errorComponents(const StepControl& control, const OdeSystem& system);

/// The weighted RMS norm of StepControl over the first `components` entries
/// (errorComponents) for a local error estimate `err` of the step y0 -> y1; <= 1 means the
/// step is accepted. NaN propagates (and is then rejected).
/// Inline: once per step attempt, in the integrators' inner loop.
inline double errorNorm(const OdeVector& err, const OdeVector& y0, const OdeVector& y1, const StepControl& control,
                        int components) {
  double sum = 0.0;
  for (int i = 0; i < components; ++i) {
    const double scale = control.abs_tol + control.rel_tol * std::max(std::abs(y0[i]), std::abs(y1[i]));
    const double r = err[i] / scale;
    sum += r * r;
  }
  return std::sqrt(sum / components);
}

/// Throws climbsim::ConfigError naming the field when a StepControl value is out of range.
void validateStepControl(const StepControl& control);

/// The step-size control shared by the adaptive integrators over [0, t_end_s]: proposes
/// trial steps (stretching the last one by up to 1 % instead of leaving a sliver at the
/// interval end) and judges them with the standard controller
///   fac = safety * norm^(-1/error_order), clamped to [fac_min, fac_max],
/// accepting when norm <= 1 and never growing a step right after a rejection
/// (Hairer, Norsett & Wanner I, II.4).
class AdaptiveSteps {
 public:
  /// `method` names the integrator in error messages; `initial_step_s` is clamped.
  AdaptiveSteps(const StepControl& control, double error_order, double fac_max, const char* method, double t_end_s,
                double initial_step_s);

  bool done() const { return t_ >= t_end_s_; }
  /// Local time at the start of the current trial [s].
  double t() const { return t_; }
  /// Size of the next trial step [s]; throws std::runtime_error after control.max_steps trials.
  double trial();
  /// What trial() will return next, without counting a trial [s].
  double peekTrial() const;
  /// Accepts (true: t advances by the trial) or rejects the last trial; updates the step
  /// size; throws std::runtime_error when the step underflows.
  bool judge(double norm, bool finite, IntegratorStats& stats);
  /// The step size to start the next interval with [s].
  double proposal() const { return h_; }
  /// Throws std::runtime_error naming the method, the time and the step.
  [[noreturn]] void fail(const char* what) const;

 private:
  const StepControl& control_;
  double error_order_;
  double fac_max_;
  const char* method_;
  double t_end_s_;
  double t_ = 0.0;
  double h_;
  double h_try_ = 0.0;
  bool last_ = false;
  bool rejected_last_ = false;
  long steps_ = 0;
  static constexpr double kSafety = 0.9;
  static constexpr double kFacMin = 0.2;
};

// Inline: called once per step attempt.
inline double AdaptiveSteps::peekTrial() const {
  const double remaining = t_end_s_ - t_;
  return h_ >= remaining * 0.99 ? remaining : h_;
}

inline double AdaptiveSteps::trial() {
  if (++steps_ > control_.max_steps) fail("too many steps");
  const double remaining = t_end_s_ - t_;
  last_ = h_ >= remaining * 0.99;
  h_try_ = last_ ? remaining : h_;
  return h_try_;
}

inline bool AdaptiveSteps::judge(double norm, bool finite, IntegratorStats& stats) {
  const double clipped = std::max(norm, 1e-10);
  double fac = !finite ? kFacMin
               : error_order_ == 2.0 ? kSafety / std::sqrt(clipped)
                                     : kSafety * std::pow(clipped, -1.0 / error_order_);
  fac = std::clamp(fac, kFacMin, fac_max_);
  if (finite && norm <= 1.0) {
    ++stats.accepted_steps;
    t_ = last_ ? t_end_s_ : t_ + h_try_;
    double h_next = h_try_ * fac;
    if (rejected_last_) h_next = std::min(h_next, h_try_);
    // A step shortened to meet the interval end says little about the step to come.
    if (last_ && h_try_ < h_) h_next = std::max(h_next, h_);
    h_ = std::clamp(h_next, control_.min_step_s, control_.max_step_s);
    rejected_last_ = false;
    return true;
  }
  ++stats.rejected_steps;
  rejected_last_ = true;
  h_ = h_try_ * fac;
  if (h_ < control_.min_step_s) fail(finite ? "step size underflow" : "non-finite state");
  return false;
}

}  // namespace climbsim::thermo
