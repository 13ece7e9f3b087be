/* climbsim-c-valves: an adhesion controller in C on Cyclone DDS's C API (types by idlc from
 * idl/thermo.idl and idl/clock.idl). A roster member of the lockstep clock: each due step it
 * reads ChamberState and AdhesionForce of the thermo service and writes ValveCommand.
 * Run it with the scenario controller type `external` (deploy/compose.c-controller.yaml):
 * climbsim-controller then still drives and runs the engines but leaves the valves to it.
 *
 * Control law (the reference controller's force and valve loops, without its balance loop):
 *   force loop:  d s_base/dt = (F* - F) / (A * force_tau_s), s_base in [0, max_suction_pa],
 *                held while the reservoir cannot deliver more (s_R <= s_base and F < F*);
 *   valve loop:  d u_i/dt = gain * (min(s_base, 0.9 s_R) - s_i), u_i in [0, 1], every chamber,
 * with s = p_o - p the suction of a chamber [Pa], s_R the reservoir's, A the sealed area [m^2].
 *
 *   climbsim-c-valves --name NAME --domain D [--period N --offset K] [--downforce-n F]
 *                     [--sealed-area-m2 A] [--ambient-pa P] [--start-timeout-s S]
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
  int state_input, force_input, valve_output;
  uint64_t steps;
} controller;

static double clamp(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

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
  if (c->valves == 0) {
    /* The run's robot comes with RunStart: one valve per chamber on a reservoir. */
    const climbsim_RunStart* start = p->run_start;
    const uint32_t n = start->robot.chambers._length;
    if (!start->robot.has_reservoir || n == 0 || n > MAX_VALVES) {
      return snprintf(why, why_size, "robot '%s' has %u chambers%s: this controller sets one valve per chamber on a "
                      "reservoir", start->robot.name, (unsigned)n, start->robot.has_reservoir ? "" : " and no reservoir"), 1;
    }
    c->valves = n;
  }
  if (state != NULL && (state->valve_opening._length != c->valves || state->pressure_pa._length != c->valves + 1)) {
    return snprintf(why, why_size, "thermo/ChamberState from '%s' has %u pressures and %u valve openings; robot of %u "
                    "chambers on a reservoir", state->source, (unsigned)state->pressure_pa._length,
                    (unsigned)state->valve_opening._length, (unsigned)c->valves), 1;
  }
  if (state != NULL && force != NULL && isfinite(force->downforce_n) && isfinite(state->pressure_pa._buffer[c->valves])) {
    const double reservoir_suction_pa = c->ambient_pa - state->pressure_pa._buffer[c->valves];
    const double error_n = c->desired_downforce_n - force->downforce_n;
    if (!(error_n > 0.0 && reservoir_suction_pa <= c->s_base_pa)) {
      c->s_base_pa = clamp(c->s_base_pa + dt_s * error_n / (c->sealed_area_m2 * c->force_tau_s), 0.0, c->max_suction_pa);
    }
    const double target_pa = fmin(c->s_base_pa, 0.9 * reservoir_suction_pa);
    for (uint32_t i = 0; i < c->valves; ++i) {
      if (!isfinite(state->pressure_pa._buffer[i])) continue;
      const double suction_pa = c->ambient_pa - state->pressure_pa._buffer[i];
      c->opening[i] = clamp(c->opening[i] + dt_s * c->valve_gain_per_pa_s * (target_pa - suction_pa), 0.0, 1.0);
    }
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
    fprintf(stderr, "%s: step %llu: F = %.1f N (F* %.0f N), s_base %.0f Pa\n", p->name,
            (unsigned long long)s->step, force->downforce_n, c->desired_downforce_n, c->s_base_pa);
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
  c.sealed_area_m2 = 3.14159265358979323846 * 0.36 * 0.36; /* cromsci: sealed diameter 0.72 m */
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
      case 'q': break; /* the C++ services' QoS file: this client builds the same QoS itself */
      case 'h':
        printf("usage: climbsim-c-valves --name NAME --domain D [--period N] [--offset K] [--downforce-n F]\n"
               "       [--sealed-area-m2 A] [--ambient-pa P] [--start-timeout-s S]\n");
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
  c.s_base_pa = clamp(c.desired_downforce_n / c.sealed_area_m2, 0.0, c.max_suction_pa);

  cl_participant p;
  if (cl_init(&p, name, domain, (uint32_t)period, (uint32_t)offset, start_timeout_s) != 0) {
    cl_fini(&p);
    return CL_EXIT_CONFIG;
  }
  c.state_input = cl_input(&p, CLIMBSIM_TOPIC_CHAMBER_STATE, &climbsim_ChamberState_desc, sizeof(climbsim_ChamberState));
  c.force_input = cl_input(&p, CLIMBSIM_TOPIC_ADHESION_FORCE, &climbsim_AdhesionForce_desc, sizeof(climbsim_AdhesionForce));
  c.valve_output = cl_output(&p, CLIMBSIM_TOPIC_VALVE_COMMAND, &climbsim_ValveCommand_desc);
  if (c.state_input < 0 || c.force_input < 0 || c.valve_output < 0) {
    cl_fini(&p);
    return CL_EXIT_FAILED;
  }
  fprintf(stderr, "%s: C valve controller on Cyclone DDS, F* = %.0f N, domain %d\n", name, c.desired_downforce_n, domain);
  const int code = cl_run(&p, step, &c);
  cl_fini(&p);
  return code;
}
