#include "climbsim_engine_law.h"

#include <math.h>

static double clamp(double v, double lo, double hi) { return v < lo ? lo : hi < v ? hi : v; }
static double max0(double v) { return 0.0 < v ? v : 0.0; }

void cl_engine_law_step(cl_engine_law* law, const double* pressure_pa, const double pf_m[2], double dt_s) {
  /* 1. What the chambers without an engine pull by themselves. */
  double unpumped_force_n = 0.0;
  for (uint32_t i = 0; i < law->chambers; ++i) {
    if (!law->pumped[i]) unpumped_force_n += law->area_m2[i] * max0(law->ambient_pa - pressure_pa[i]);
  }
  /* 2. Balance trims of the pumped chambers off the centre. */
  for (uint32_t i = 0; i < law->chambers; ++i) {
    const double cx = law->centroid_m[i][0], cy = law->centroid_m[i][1];
    const double r2_m2 = cx * cx + cy * cy;
    if (!law->balance || !law->pumped[i] || r2_m2 <= 1e-18) {
      law->trim[i] = 0.0;
      continue;
    }
    const double towards = (pf_m[0] * cx + pf_m[1] * cy) / r2_m2;
    int saturated = towards < 0.0;
    for (uint32_t k = 0; k < law->engines; ++k) {
      if (law->engine_chamber[k] == i) saturated = saturated && law->speed[k] >= 1.0;
    }
    if (!saturated) law->trim[i] = clamp(law->trim[i] + dt_s * towards / law->balance_tau_s, -law->max_trim, law->max_trim);
  }
  /* 3. The pumped chambers' shares of F*. */
  double weighted_area_m2 = 0.0;
  for (uint32_t i = 0; i < law->chambers; ++i) {
    if (law->pumped[i]) weighted_area_m2 += law->area_m2[i] * (1.0 - law->trim[i]);
  }
  const double common_pa = max0(law->desired_downforce_n - unpumped_force_n) / weighted_area_m2;
  for (uint32_t i = 0; i < law->chambers; ++i) {
    const double share_pa = common_pa * (1.0 - law->trim[i]);
    law->target_pa[i] = law->pumped[i] ? (law->max_suction_pa < share_pa ? law->max_suction_pa : share_pa) : 0.0;
  }
  /* 4. Each engine's PI on its chamber's normalised error, with the fan curve's feed-forward. */
  for (uint32_t k = 0; k < law->engines; ++k) {
    const uint32_t c = law->engine_chamber[k];
    const double target_pa = law->target_pa[c];
    const double error = (target_pa - (law->ambient_pa - pressure_pa[c])) / law->max_suction_pa;
    const double feedforward = sqrt(target_pa / law->max_suction_pa);
    law->speed[k] = clamp(law->speed[k] + (feedforward - law->last_feedforward[k]) +
                              law->engine_prop * (error - law->last_error[k]) + dt_s * error / law->engine_integral_s,
                          0.0, 1.0);
    law->last_error[k] = error;
    law->last_feedforward[k] = feedforward;
  }
}
