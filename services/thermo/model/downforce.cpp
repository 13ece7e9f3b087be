#include "downforce.hpp"

namespace climbsim::thermo {

Downforce computeDownforce(const ThermoParams& params, const std::vector<double>& pressure_pa) {
  Downforce out;
  double area_sum = 0.0;
  std::array<double, 2> area_moment{};
  const int chambers = params.chamberCount();
  for (int i = 0; i < chambers; ++i) {
    const double area = params.chamber_area_m2[i];
    const double force = (params.gas.ambient_pressure_pa - pressure_pa[i]) * area;
    out.force_n += force;
    area_sum += area;
    for (int k = 0; k < 2; ++k) {
      out.moment_nm[k] += params.p_RobotChamber_m[i][k] * force;
      area_moment[k] += params.p_RobotChamber_m[i][k] * area;
    }
  }
  for (int k = 0; k < 2; ++k) {
    out.p_RobotPF_m[k] = out.force_n > 0.0 ? out.moment_nm[k] / out.force_n : area_moment[k] / area_sum;
  }
  return out;
}

}  // namespace climbsim::thermo
