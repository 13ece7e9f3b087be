#pragma once
/// @file
/// Downforce and its point of action from the chamber pressures
/// (docs/design.md#airflow-and-downforce).

#include <array>
#include <vector>

#include "thermo_params.hpp"

namespace climbsim::thermo {

/// Adhesion produced by the chambers.
struct Downforce {
  double force_n = 0.0;                  ///< F = sum_i (p_o - p_i) A_i [N]
  std::array<double, 2> moment_nm{};     ///< M = sum_i P_i (p_o - p_i) A_i [N m], robot frame
  std::array<double, 2> p_RobotPF_m{};   ///< M / F if F > 0, else the suction-area centroid [m]
};

/// F, M and P_F for chamber pressures pressure_pa[0..N-1] (a reservoir entry after them is
/// ignored).
/// With F <= 0 nothing pulls the robot to the wall and M / F is meaningless (infinite at
/// F = 0); P_F is then sum_i P_i A_i / sum_i A_i, where a uniform pressure would act.
Downforce computeDownforce(const ThermoParams& params, const std::vector<double>& pressure_pa);

}  // namespace climbsim::thermo
