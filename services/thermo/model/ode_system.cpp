#include "ode_system.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include "climbsim/errors.hpp"

namespace climbsim::thermo {

double errorNorm(const OdeVector& err, const OdeVector& y0, const OdeVector& y1, const StepControl& control) {
  double sum = 0.0;
  for (int i = 0; i < control.error_components; ++i) {
    const double scale = control.abs_tol + control.rel_tol * std::max(std::abs(y0[i]), std::abs(y1[i]));
    const double r = err[i] / scale;
    sum += r * r;
  }
  return std::sqrt(sum / control.error_components);
}

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
}

}  // namespace climbsim::thermo
