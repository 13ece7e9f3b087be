#include "ode_system.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include "climbsim/errors.hpp"

namespace climbsim::thermo {

void validateStepControl(const StepControl& c) {
  auto fail = [](const char* key, double value, const char* rule) {
    std::ostringstream os;
    os << "thermo: integrator." << key << " = " << value << " (must be " << rule << ")";
    throw ConfigError(os.str());
  };
  if (!(c.abs_tol > 0.0) || !std::isfinite(c.abs_tol)) fail("abs_tol", c.abs_tol, "finite and > 0");
  if (!(c.rel_tol >= 0.0) || !std::isfinite(c.rel_tol)) fail("rel_tol", c.rel_tol, "finite and >= 0");
  if (c.error_components < 1 || c.error_components > kOdeSize) fail("error_components", c.error_components, "in 1..10");
  if (!(c.min_step_s > 0.0) || !std::isfinite(c.min_step_s)) fail("min_step_s", c.min_step_s, "finite and > 0");
  if (!(c.max_step_s > c.min_step_s) || !std::isfinite(c.max_step_s)) fail("max_step_s", c.max_step_s, "finite and > min_step_s");
  if (c.max_steps < 1) fail("max_steps", static_cast<double>(c.max_steps), ">= 1");
  if (!(c.explicit_below >= 0.0 && c.explicit_below <= 2.0)) fail("explicit_below", c.explicit_below, "in [0, 2]");
  if (!(c.euler_below >= 0.0 && c.euler_below <= 1.0)) fail("euler_below", c.euler_below, "in [0, 1]");
}

double OdeSystem::rhsWithStiffness(double t_s, const OdeVector& y, OdeVector& dydt) const {
  OdeMatrix dfdy;
  OdeVector dfdt;
  jacobian(t_s, y, dydt, dfdy, dfdt);
  return stiffnessBound(dfdy);
}

double OdeSystem::stiffnessBound(const OdeMatrix& dfdy) const {
  double bound = 0.0;
  for (int i = 0; i < kCoupledSize; ++i) {
    bound = std::max(bound, dfdy.row(i).head<kCoupledSize>().cwiseAbs().sum());
  }
  return bound;
}

namespace {
constexpr double kSafety = 0.9;
constexpr double kFacMin = 0.2;
}  // namespace

AdaptiveSteps::AdaptiveSteps(const StepControl& control, double error_order, double fac_max, const char* method,
                             double t_end_s, double initial_step_s)
    : control_(control),
      error_order_(error_order),
      fac_max_(fac_max),
      method_(method),
      t_end_s_(t_end_s),
      h_(std::clamp(initial_step_s, control.min_step_s, control.max_step_s)) {}

void AdaptiveSteps::fail(const char* what) const {
  std::ostringstream os;
  os << "thermo: " << method_ << " integration failed at local t = " << t_ << " s with step " << h_ << " s: " << what;
  throw std::runtime_error(os.str());
}

double AdaptiveSteps::peekTrial() const {
  const double remaining = t_end_s_ - t_;
  return h_ >= remaining * 0.99 ? remaining : h_;
}

double AdaptiveSteps::trial() {
  if (++steps_ > control_.max_steps) fail("too many steps");
  const double remaining = t_end_s_ - t_;
  last_ = h_ >= remaining * 0.99;
  h_try_ = last_ ? remaining : h_;
  return h_try_;
}

bool AdaptiveSteps::judge(double norm, bool finite, IntegratorStats& stats) {
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
