#include "ode_system.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
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
  if (c.error_components < 0 || c.error_components > kMaxOdeSize) {
    fail("error_components", c.error_components, "in 0..27 (0: every pressure)");
  }
  if (!(c.min_step_s > 0.0) || !std::isfinite(c.min_step_s)) fail("min_step_s", c.min_step_s, "finite and > 0");
  if (!(c.max_step_s > c.min_step_s) || !std::isfinite(c.max_step_s)) fail("max_step_s", c.max_step_s, "finite and > min_step_s");
  if (c.max_steps < 1) fail("max_steps", static_cast<double>(c.max_steps), ">= 1");
  if (!(c.explicit_below >= 0.0 && c.explicit_below <= 2.0)) fail("explicit_below", c.explicit_below, "in [0, 2]");
  if (!(c.euler_below >= 0.0 && c.euler_below <= 1.0)) fail("euler_below", c.euler_below, "in [0, 1]");
}

OdeSystem::OdeSystem(int size, int coupled_size) : size_(size), coupled_size_(coupled_size) {
  if (size < 1 || size > kMaxOdeSize || coupled_size < 1 || coupled_size > size) {
    throw std::invalid_argument("thermo: an ODE of " + std::to_string(size) + " entries, " +
                                std::to_string(coupled_size) + " coupled (1..27 entries, 1..size coupled)");
  }
}

int errorComponents(const StepControl& control, const OdeSystem& system) {
  if (control.error_components == 0) return system.coupledSize();
  if (control.error_components > system.size()) {
    throw std::invalid_argument("thermo: integrator.error_components = " + std::to_string(control.error_components) +
                                " for an ODE of " + std::to_string(system.size()) + " entries");
  }
  return control.error_components;
}

double OdeSystem::rhsWithStiffness(double t_s, const OdeVector& y, OdeVector& dydt) const {
  OdeMatrix dfdy(size_, size_);
  OdeVector dfdt(size_);
  jacobian(t_s, y, dydt, dfdy, dfdt);
  return stiffnessBound(dfdy);
}

double OdeSystem::stiffnessBound(const OdeMatrix& dfdy) const {
  double bound = 0.0;
  for (int i = 0; i < coupled_size_; ++i) {
    bound = std::max(bound, dfdy.row(i).head(coupled_size_).cwiseAbs().sum());
  }
  return bound;
}

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

}  // namespace climbsim::thermo
