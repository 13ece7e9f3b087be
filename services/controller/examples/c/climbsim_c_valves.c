/* climbsim-c-valves: an adhesion controller in C on Cyclone DDS's C API (types by idlc from
 * idl/thermo.idl and idl/clock.idl). A roster member of the lockstep clock: each due step it
 * reads ChamberState and AdhesionForce of the thermo service and writes ValveCommand (and, with
 * --engines, EngineCommand). Run it with the scenario controller type `external`
 * (deploy/compose.c-controller.yaml): climbsim-controller then still drives (and, on a robot
 * with a reservoir, runs the engines) but leaves the valves, or the engines, to it. The robot
 * comes with RunStart (idl/clock.idl RobotShape): its chambers' areas and centroids, reservoir
 * and engines.
 *
 * With a reservoir, one valve per chamber (the reference controller's force and valve loops,
 * without its balance loop):
 *   force loop:  d s_base/dt = (F* - F) / (A * force_tau_s), s_base in [0, max_suction_pa],
 *                held while the reservoir cannot deliver more (s_R <= s_base and F < F*);
 *   valve loop:  d u_i/dt = gain * (min(s_base, 0.9 s_R) - s_i), u_i in [0, 1], every chamber,
 * with s = p_o - p the suction of a chamber [Pa], s_R the reservoir's, A the sealed area [m^2]
 * (the chambers' areas summed, or --sealed-area-m2).
 * Without a reservoir (start it with --engines): the reference controller's engine law
 * (climbsim_engine_law.h), the same numbers as climbsim-controller's; the ValveCommand then has
 * no openings and carries the set-point.
 *
 *   climbsim-c-valves --name NAME --domain D [--period N --offset K] [--downforce-n F] [--engines]
 *                     [--sealed-area-m2 A] [--ambient-pa P] [--start-timeout-s S]
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "climbsim_engine_law.h"
#include "climbsim_lockstep.h"
#include "clock.h"
#include "thermo.h"

/* Most chambers a robot may have (the bound of ValveCommand.opening in idl/thermo.idl). The
 * robot's own count comes with RunStart (its RobotShape): one valve per chamber. */
#define MAX_VALVES 24

typedef struct {
  double desired_downforce_n;   /* F* [N] */
  double sealed_area_m2;        /* A: suction area of all chambers [m^2] */
  double ambient_pa;            /* p_o [Pa] */
  double max_suction_pa;        /* limit of s_base [Pa] */
  double force_tau_s;           /* force loop integral time [s] */
  double valve_gain_per_pa_s;   /* valve loop integral gain [1/(Pa s)] */
  double s_base_pa;             /* state: common suction target [Pa] */
  double opening[MAX_VALVES];   /* state: commanded openings, 0..1 */
  uint32_t valves;              /* the robot's chamber count, from RunStart */
  int sized;                    /* sized from RunStart's robot */
  int engines;                  /* --engines: the robot has no reservoir, the engine law commands its engines */
  cl_engine_law law;            /* --engines: the law's parameters and state */
  double held_pressure_pa[CL_ENGINE_LAW_MAX_CHAMBERS]; /* --engines: the last valid pressures [Pa] */
  double held_pf_m[2];          /* --engines: the last valid P_F [m] */
  int state_input, force_input, valve_output, engine_output;
  uint64_t steps;
} controller;

static double clamp(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

/* Sizes the controller from RunStart's robot; NULL, or why the robot does not fit. */
static const char* size_from_robot(controller* c, const climbsim_RunStart* start) {
  static char problem[256];
  const climbsim_RobotShape* robot = &start->robot;
  const uint32_t n = robot->chambers._length;
  if (n == 0 || n > MAX_VALVES) {
    snprintf(problem, sizeof(problem), "robot '%s' has %u chambers (this controller takes 1..%d)", robot->name,
             (unsigned)n, MAX_VALVES);
    return problem;
  }
  if (robot->has_reservoir == (c->engines != 0)) {
    snprintf(problem, sizeof(problem), robot->has_reservoir
                 ? "robot '%s' has a reservoir and valves: start climbsim-c-valves without --engines"
                 : "robot '%s' has no reservoir and so no valves: start climbsim-c-valves with --engines to "
                   "command its engines",
             robot->name);
    return problem;
  }
  double area_m2 = 0.0;
  for (uint32_t i = 0; i < n; ++i) area_m2 += robot->chambers._buffer[i].area_m2;
  if (c->sealed_area_m2 <= 0.0) c->sealed_area_m2 = area_m2;
  c->s_base_pa = clamp(c->desired_downforce_n / c->sealed_area_m2, 0.0, c->max_suction_pa);
  if (!c->engines) {
    c->valves = n;
    c->sized = 1;
    return NULL;
  }
  cl_engine_law* law = &c->law;
  const uint32_t engines = robot->engine_chambers._length;
  if (engines == 0 || engines > CL_ENGINE_LAW_MAX_ENGINES || engines != robot->engine_count) {
    snprintf(problem, sizeof(problem), "robot '%s': %u engines name their chambers for %u engines", robot->name,
             (unsigned)engines, (unsigned)robot->engine_count);
    return problem;
  }
  law->chambers = n;
  law->engines = engines;
  for (uint32_t i = 0; i < n; ++i) c->held_pressure_pa[i] = c->ambient_pa;
  law->ambient_pa = c->ambient_pa;
  for (uint32_t i = 0; i < n; ++i) {
    law->area_m2[i] = robot->chambers._buffer[i].area_m2;
    law->centroid_m[i][0] = robot->chambers._buffer[i].centroid_x_m;
    law->centroid_m[i][1] = robot->chambers._buffer[i].centroid_y_m;
  }
  for (uint32_t k = 0; k < engines; ++k) {
    const uint32_t chamber = robot->engine_chambers._buffer[k];
    if (chamber < 1 || chamber > n) {
      snprintf(problem, sizeof(problem), "robot '%s': engine %u pumps chamber %u of %u", robot->name, (unsigned)k + 1,
               (unsigned)chamber, (unsigned)n);
      return problem;
    }
    law->engine_chamber[k] = chamber - 1;
    law->pumped[chamber - 1] = 1;
  }
  law->desired_downforce_n = c->desired_downforce_n;
  law->balance = 1;
  law->max_suction_pa = robot->engine_dp_max_pa;
  /* At least 0.05 s, as kMinEngineIntegralS of services/controller/model/engine_controller.hpp. */
  law->engine_integral_s = robot->engine_speed_lag_s > 0.05 ? robot->engine_speed_lag_s : 0.05;
  law->engine_prop = 1.0;
  law->balance_tau_s = 1.0;
  law->max_trim = 0.5;
  c->sized = 1;
  return NULL;
}

static int step(cl_participant* p, const cl_step* s, void* user, char* why, size_t why_size) {
  controller* c = user;
  /* One producer of each (thermo); with several, the last by name wins as in the C++ node. */
  const climbsim_ChamberState* state = NULL;
  const climbsim_AdhesionForce* force = NULL;
  for (size_t k = 0; k < cl_producer_count(p, c->state_input); ++k) {
    const void* got = NULL;
    if (cl_get(p, c->state_input, k, s, &got) != 0) return snprintf(why, why_size, "no ChamberState"), 1;
    if (got != NULL) state = got;
  }
  for (size_t k = 0; k < cl_producer_count(p, c->force_input); ++k) {
    const void* got = NULL;
    if (cl_get(p, c->force_input, k, s, &got) != 0) return snprintf(why, why_size, "no AdhesionForce"), 1;
    if (got != NULL) force = got;
  }
  const double dt_s = 1e-9 * (double)s->dt_ns * p->period_steps;
  if (!c->sized) {
    const char* problem = size_from_robot(c, p->run_start);
    if (problem != NULL) return snprintf(why, why_size, "%s", problem), 1;
  }
  const uint32_t volumes = c->engines ? c->law.chambers : c->valves + 1;
  if (state != NULL && (state->valve_opening._length != c->valves || state->pressure_pa._length != volumes)) {
    return snprintf(why, why_size, "thermo/ChamberState from '%s' has %u pressures and %u valve openings; robot of %u "
                    "chambers %s", state->source, (unsigned)state->pressure_pa._length,
                    (unsigned)state->valve_opening._length, (unsigned)(c->engines ? c->law.chambers : c->valves),
                    c->engines ? "without a reservoir" : "on a reservoir"), 1;
  }
  int finite = state != NULL && force != NULL && isfinite(force->downforce_n);
  for (uint32_t i = 0; finite && i < volumes; ++i) finite = isfinite(state->pressure_pa._buffer[i]);
  if (c->engines) {
    /* As climbsim-controller: the law steps every period on the last valid measurement held
     * (before the first: ambient pressure, P_F at the centre). */
    int pressures_finite = state != NULL;
    for (uint32_t i = 0; pressures_finite && i < volumes; ++i) pressures_finite = isfinite(state->pressure_pa._buffer[i]);
    if (pressures_finite) memcpy(c->held_pressure_pa, state->pressure_pa._buffer, volumes * sizeof(double));
    if (force != NULL && isfinite(force->downforce_n) && isfinite(force->pf_x_m) && isfinite(force->pf_y_m)) {
      c->held_pf_m[0] = force->pf_x_m;
      c->held_pf_m[1] = force->pf_y_m;
    }
    cl_engine_law_step(&c->law, c->held_pressure_pa, c->held_pf_m, dt_s);
  } else if (finite) {
    const double reservoir_suction_pa = c->ambient_pa - state->pressure_pa._buffer[c->valves];
    const double error_n = c->desired_downforce_n - force->downforce_n;
    if (!(error_n > 0.0 && reservoir_suction_pa <= c->s_base_pa)) {
      c->s_base_pa = clamp(c->s_base_pa + dt_s * error_n / (c->sealed_area_m2 * c->force_tau_s), 0.0, c->max_suction_pa);
    }
    const double target_pa = fmin(c->s_base_pa, 0.9 * reservoir_suction_pa);
    for (uint32_t i = 0; i < c->valves; ++i) {
      const double suction_pa = c->ambient_pa - state->pressure_pa._buffer[i];
      c->opening[i] = clamp(c->opening[i] + dt_s * c->valve_gain_per_pa_s * (target_pa - suction_pa), 0.0, 1.0);
    }
  }
  if (c->engines) {
    climbsim_EngineSetting settings[CL_ENGINE_LAW_MAX_ENGINES];
    for (uint32_t k = 0; k < c->law.engines; ++k) {
      settings[k].on = true;
      settings[k].speed = c->law.speed[k];
    }
    climbsim_EngineCommand engines;
    memset(&engines, 0, sizeof(engines));
    engines.engines._maximum = c->law.engines;
    engines.engines._length = c->law.engines;
    engines.engines._buffer = settings;
    engines.engines._release = false;
    if (cl_write(p, c->engine_output, &engines, s) != 0) return snprintf(why, why_size, "cannot write EngineCommand"), 1;
  }
  climbsim_ValveCommand cmd;
  memset(&cmd, 0, sizeof(cmd));
  cmd.opening._maximum = c->valves;
  cmd.opening._length = c->valves;
  cmd.opening._buffer = c->opening;
  cmd.opening._release = false;
  cmd.downforce_setpoint_n = c->desired_downforce_n; /* the trace and the plots show this set-point */
  if (cl_write(p, c->valve_output, &cmd, s) != 0) return snprintf(why, why_size, "cannot write ValveCommand"), 1;
  if (++c->steps % 1000 == 0 && force != NULL) {
    fprintf(stderr, "%s: step %llu: F = %.1f N (F* %.0f N), s_base %.0f Pa, engine 1 at %.3f\n", p->name,
            (unsigned long long)s->step, force->downforce_n, c->desired_downforce_n, c->s_base_pa,
            c->engines ? c->law.speed[0] : 1.0);
  }
  return 0;
}

/* Parses a number option; exits 2 with one line naming it on bad input. */
static double number(const char* option, const char* text, double lo, double hi) {
  char* end = NULL;
  errno = 0;
  const double v = strtod(text, &end);
  if (errno != 0 || end == text || *end != '\0' || !isfinite(v) || v < lo || v > hi) {
    fprintf(stderr, "climbsim-c-valves: error: %s = '%s': expected a number in [%g, %g]\n", option, text, lo, hi);
    exit(CL_EXIT_CONFIG);
  }
  return v;
}

int main(int argc, char** argv) {
  const char* name = NULL;
  const char* domain_text = getenv("CLIMBSIM_DOMAIN");
  double period = 1, offset = 0, start_timeout_s = 60;
  controller c;
  memset(&c, 0, sizeof(c));
  c.desired_downforce_n = 2200.0;
  c.sealed_area_m2 = 0.0; /* the robot's chambers' areas summed (RunStart) */
  c.ambient_pa = 100000.0;
  c.max_suction_pa = 22000.0;
  c.force_tau_s = 1.0;
  c.valve_gain_per_pa_s = 1e-4;
  static const struct option options[] = {
      {"name", required_argument, 0, 'n'},           {"domain", required_argument, 0, 'd'},
      {"period", required_argument, 0, 'p'},         {"offset", required_argument, 0, 'o'},
      {"start-timeout-s", required_argument, 0, 't'}, {"downforce-n", required_argument, 0, 'f'},
      {"sealed-area-m2", required_argument, 0, 'a'}, {"ambient-pa", required_argument, 0, 'b'},
      {"qos", required_argument, 0, 'q'},            {"help", no_argument, 0, 'h'},
      {"engines", no_argument, 0, 'e'},
      {0, 0, 0, 0}};
  int opt;
  while ((opt = getopt_long(argc, argv, "h", options, NULL)) != -1) {
    switch (opt) {
      case 'n': name = optarg; break;
      case 'd': domain_text = optarg; break;
      case 'p': period = number("--period", optarg, 1, 1e6); break;
      case 'o': offset = number("--offset", optarg, 0, 1e6); break;
      case 't': start_timeout_s = number("--start-timeout-s", optarg, 1e-3, 1e6); break;
      case 'f': c.desired_downforce_n = number("--downforce-n", optarg, 1, 1e6); break;
      case 'a': c.sealed_area_m2 = number("--sealed-area-m2", optarg, 1e-6, 100); break;
      case 'b': c.ambient_pa = number("--ambient-pa", optarg, 1, 1e7); break;
      case 'e': c.engines = 1; break;
      case 'q': break; /* the C++ services' QoS file: this client builds the same QoS itself */
      case 'h':
        printf("usage: climbsim-c-valves --name NAME --domain D [--period N] [--offset K] [--downforce-n F]\n"
               "       [--engines] [--sealed-area-m2 A] [--ambient-pa P] [--start-timeout-s S]\n"
               "  --engines: the robot has no reservoir: command its engines by the reference controller's engine law\n");
        return 0;
      default: return CL_EXIT_CONFIG;
    }
  }
  if (name == NULL || domain_text == NULL) {
    fprintf(stderr, "climbsim-c-valves: error: %s is required\n", name == NULL ? "--name" : "--domain (or CLIMBSIM_DOMAIN)");
    return CL_EXIT_CONFIG;
  }
  const int domain = (int)number("--domain", domain_text, 0, 232);
  if (period != floor(period) || offset != floor(offset)) {
    fprintf(stderr, "climbsim-c-valves: error: --period and --offset must be whole numbers\n");
    return CL_EXIT_CONFIG;
  }

  cl_participant p;
  if (cl_init(&p, name, domain, (uint32_t)period, (uint32_t)offset, start_timeout_s) != 0) {
    cl_fini(&p);
    return CL_EXIT_CONFIG;
  }
  c.state_input = cl_input(&p, CLIMBSIM_TOPIC_CHAMBER_STATE, &climbsim_ChamberState_desc, sizeof(climbsim_ChamberState));
  c.force_input = cl_input(&p, CLIMBSIM_TOPIC_ADHESION_FORCE, &climbsim_AdhesionForce_desc, sizeof(climbsim_AdhesionForce));
  c.valve_output = cl_output(&p, CLIMBSIM_TOPIC_VALVE_COMMAND, &climbsim_ValveCommand_desc);
  c.engine_output = c.engines ? cl_output(&p, CLIMBSIM_TOPIC_ENGINE_COMMAND, &climbsim_EngineCommand_desc) : 0;
  if (c.state_input < 0 || c.force_input < 0 || c.valve_output < 0 || c.engine_output < 0) {
    cl_fini(&p);
    return CL_EXIT_FAILED;
  }
  fprintf(stderr, "%s: C %s controller on Cyclone DDS, F* = %.0f N, domain %d\n", name, c.engines ? "engine" : "valve",
          c.desired_downforce_n, domain);
  const int code = cl_run(&p, step, &c);
  cl_fini(&p);
  return code;
}
