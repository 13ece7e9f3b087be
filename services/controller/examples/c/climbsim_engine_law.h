/* The reference controller's engine law for robots without a reservoir, in C: a line-by-line
 * port of services/controller/model/engine_controller.cpp (same operations in the same order, so
 * the same numbers bit for bit; the header there has the equations, docs/controllers.md the law
 * in short). s_i = p_o - p_i the suction of chamber i [Pa], A_i its area, omega_k engine k's
 * speed command in [0, 1], on chamber c_k. Each step:
 *   F_u = sum over the chambers no engine pumps of A_i max(0, s_i);
 *   trims b_i of the pumped chambers off the centre: d b_i/dt = (P_F . P_i) / (r_i^2 tau_b),
 *     held while every engine on the chamber runs at full speed and the trim would ask for more;
 *   s*_i = min(s_F (1 - b_i), s_max), s_F = max(0, F* - F_u) / sum A_i (1 - b_i);
 *   e_k = (s*_c - s_c) / s_max, omega_ff = sqrt(s*_c / s_max),
 *   omega_k += (omega_ff - omega_ff,prev) + K_P (e_k - e_k,prev) + dt e_k / tau_I, in [0, 1]. */
#ifndef CLIMBSIM_ENGINE_LAW_H
#define CLIMBSIM_ENGINE_LAW_H

#include <stdint.h>

#define CL_ENGINE_LAW_MAX_CHAMBERS 24
#define CL_ENGINE_LAW_MAX_ENGINES 16

typedef struct {
  /* parameters (the robot's, from RunStart, and the set-point) */
  uint32_t chambers, engines;
  double ambient_pa;                               /* p_o [Pa] */
  double area_m2[CL_ENGINE_LAW_MAX_CHAMBERS];      /* A_i [m^2] */
  double centroid_m[CL_ENGINE_LAW_MAX_CHAMBERS][2]; /* P_i [m] */
  int pumped[CL_ENGINE_LAW_MAX_CHAMBERS];          /* chamber i has an engine */
  uint32_t engine_chamber[CL_ENGINE_LAW_MAX_ENGINES]; /* c_k, 0..N-1 */
  double desired_downforce_n;                      /* F* [N] */
  int balance;                                     /* hold P_F at the centre */
  double max_suction_pa;                           /* s_max: engines' dp_max [Pa] */
  double engine_integral_s;                        /* tau_I: engines' speed lag [s] */
  double engine_prop;                              /* K_P */
  double balance_tau_s, max_trim;
  /* state */
  double trim[CL_ENGINE_LAW_MAX_CHAMBERS];
  double target_pa[CL_ENGINE_LAW_MAX_CHAMBERS];
  double speed[CL_ENGINE_LAW_MAX_ENGINES];
  double last_error[CL_ENGINE_LAW_MAX_ENGINES];
  double last_feedforward[CL_ENGINE_LAW_MAX_ENGINES];
} cl_engine_law;

/* One step of dt_s [s] from the N chamber pressures [Pa] and P_F [m]; law->speed holds the
 * commands afterwards. */
void cl_engine_law_step(cl_engine_law* law, const double* pressure_pa, const double pf_m[2], double dt_s);

#endif
