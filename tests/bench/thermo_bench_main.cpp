/// climbsim-bench-thermo: the thermo model alone.
///
/// Scenarios (deterministic, default CROMSCI robot, 5 ms exchange period): engines on from
/// t = 0, chamber 2's outer sealing leaking 20x more between 4 s and 8 s, and
///   moving_valves    every valve following its own sine command (a new command every
///                    exchange period, so every valve ramps and lands inside every period:
///                    the worst case for the integrator);
///   controller_like  valves open, one chamber at a time throttled to 0.3 for 0.5 s.
///
///   realtime_factor  simulated seconds per wall second of ThermoModel::step with the
///                    default integrator (best of --repeat runs); met=true when >= 1000
///   implicit_only    the same ROS2 with every step implicit (explicit_below = 0,
///                    euler_below = 0): what the stiffness switch and the Euler
///                    continuation save
///   accuracy         max |p - p_ref| over every volume and exchange step, p_ref from a
///                    tight-tolerance run (Rodas3 at 1e-7 Pa, cross-checked with Dormand-Prince)
///   explicit         Dormand-Prince 5(4) at the loosest tolerance (of 10^k Pa) whose accuracy
///                    is at least the default integrator's
///   work_ratio       explicit wall time / implicit wall time (rhs_ratio: same for f evaluations,
///                    the implicit count including the f that comes with each Jacobian)
///
///   bench: thermo: realtime_factor=.. implicit_rhs_evals=.. explicit_rhs_evals=.. work_ratio=..
///
/// Options: --out FILE (JSON), --sim-s S (default 20), --repeat N (default 3),
/// --abs-tol PA (default: the model's default), --integrator ros2|rodas3 (default ros2).

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"

#include <nlohmann/json.hpp>

#include "thermo_cromsci_params.hpp"
#include "thermo_model.hpp"

using nlohmann::json;
using namespace climbsim::thermo;

namespace {

constexpr std::int64_t kExchangeNs = 5'000'000;

struct RunResult {
  std::vector<std::vector<double>> pressures;  // after every exchange step
  IntegratorStats stats;
  double wall_s = 0.0;
};

enum class Scenario {
  kMovingValves,    // every valve follows its own sine, a new command every exchange period
  kControllerLike,  // valves open, one chamber at a time throttled to 0.3 for 0.5 s
};

const char* scenarioName(Scenario sc) { return sc == Scenario::kMovingValves ? "moving_valves" : "controller_like"; }

ThermoInputs scenarioInputs(Scenario sc, const ThermoParams& p, std::int64_t t_ns) {
  const double t = static_cast<double>(t_ns) * 1e-9;
  ThermoInputs in = testing::suctionInputs(p, 1.0);
  for (int c = 0; c < p.valveCount(); ++c) {
    if (sc == Scenario::kMovingValves) {
      in.valve_command[c] = 0.5 + 0.45 * std::sin(2.0 * testing::kPi * 0.4 * t + c);
    } else {
      const double phase = std::fmod(t + 0.5 * c, 3.5);
      in.valve_command[c] = phase < 0.5 ? 0.3 : 1.0;
    }
  }
  if (t >= 4.0 && t < 8.0) in.leak_area_m2[testing::kOuterArc0 + 1] *= 20.0;
  return in;
}

RunResult runScenario(Scenario sc, const ThermoParams& params, double sim_s, bool record) {
  const ThermoModel model(params);
  ThermoState state = model.initialState();
  const auto steps = static_cast<long>(std::llround(sim_s * 1e9 / kExchangeNs));
  RunResult r;
  if (record) r.pressures.reserve(steps);
  std::vector<ThermoInputs> inputs;  // built beforehand: the clock measures the model only
  inputs.reserve(steps);
  for (long k = 0; k < steps; ++k) inputs.push_back(scenarioInputs(sc, params, k * kExchangeNs));
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    const ThermoOutputs out = model.step(state, inputs[k], state.t_ns, kExchangeNs);
    r.stats.rhs_evals += out.integrator.rhs_evals;
    r.stats.jacobian_evals += out.integrator.jacobian_evals;
    r.stats.lu_decompositions += out.integrator.lu_decompositions;
    r.stats.accepted_steps += out.integrator.accepted_steps;
    r.stats.rejected_steps += out.integrator.rejected_steps;
    r.stats.explicit_steps += out.integrator.explicit_steps;
    if (record) r.pressures.push_back(out.pressure_pa);
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// Best wall time of `repeat` runs (the trajectory and counts are identical every time).
RunResult timedRun(Scenario sc, const ThermoParams& params, double sim_s, int repeat) {
  RunResult best = runScenario(sc, params, sim_s, true);
  for (int i = 1; i < repeat; ++i) best.wall_s = std::min(best.wall_s, runScenario(sc, params, sim_s, false).wall_s);
  return best;
}

double maxError(const RunResult& a, const RunResult& ref) {
  double e = 0.0;
  for (std::size_t k = 0; k < ref.pressures.size(); ++k) {
    for (std::size_t i = 0; i < ref.pressures[k].size(); ++i) {
      e = std::max(e, std::abs(a.pressures[k][i] - ref.pressures[k][i]));
    }
  }
  return e;
}

ThermoParams withIntegrator(IntegratorKind kind, double abs_tol_pa, double rel_tol) {
  ThermoParams p = testing::defaultCromsciParams();
  p.integrator = kind;
  p.step_control.abs_tol = abs_tol_pa;
  p.step_control.rel_tol = rel_tol;
  return p;
}

json describe(const char* integrator, const ThermoParams& p, const RunResult& r, double error_pa) {
  return {{"integrator", integrator},
          {"abs_tol_pa", p.step_control.abs_tol},
          {"rel_tol", p.step_control.rel_tol},
          {"rhs_evals", r.stats.rhs_evals + r.stats.jacobian_evals},
          {"jacobian_evals", r.stats.jacobian_evals},
          {"lu_decompositions", r.stats.lu_decompositions},
          {"accepted_steps", r.stats.accepted_steps},
          {"rejected_steps", r.stats.rejected_steps},
          {"explicit_steps", r.stats.explicit_steps},
          {"wall_s", r.wall_s},
          {"max_error_pa", error_pa}};
}

struct Options {
  double sim_s = 20.0;
  int repeat = 3;
  double abs_tol = testing::defaultCromsciParams().step_control.abs_tol;
  std::string integrator = "ros2";
};

json benchScenario(Scenario sc, const Options& o) {
  const double sim_s = o.sim_s;
  const int repeat = o.repeat;
  const double abs_tol = o.abs_tol;
  const std::string& integrator = o.integrator;
  const IntegratorKind implicit_kind = integrator == "ros2" ? IntegratorKind::kRos2 : IntegratorKind::kRodas3;
  const ThermoParams ref_params = withIntegrator(IntegratorKind::kRodas3, 1e-7, 0.0);
  const RunResult ref = runScenario(sc, ref_params, sim_s, true);
  const ThermoParams check_params = withIntegrator(IntegratorKind::kDormandPrince, 1e-7, 0.0);
  const double ref_uncertainty_pa = maxError(runScenario(sc, check_params, sim_s, true), ref);

  const ThermoParams implicit_params =
      withIntegrator(implicit_kind, abs_tol, testing::defaultCromsciParams().step_control.rel_tol);
  const RunResult implicit = timedRun(sc, implicit_params, sim_s, repeat);
  const double implicit_error = maxError(implicit, ref);

  // The same method with every step implicit: what the stiffness switch buys.
  ThermoParams implicit_only_params = implicit_params;
  implicit_only_params.step_control.explicit_below = 0.0;
  implicit_only_params.step_control.euler_below = 0.0;
  const RunResult implicit_only = timedRun(sc, implicit_only_params, sim_s, repeat);

  // The other Rosenbrock tableau at the same tolerance, for docs/benchmarks.md#thermo.
  const IntegratorKind other_kind = implicit_kind == IntegratorKind::kRos2 ? IntegratorKind::kRodas3 : IntegratorKind::kRos2;
  const char* other_name = other_kind == IntegratorKind::kRos2 ? "ros2" : "rodas3";
  const ThermoParams other_params =
      withIntegrator(other_kind, implicit_params.step_control.abs_tol, implicit_params.step_control.rel_tol);
  const RunResult other = timedRun(sc, other_params, sim_s, repeat);

  ThermoParams explicit_params;
  RunResult explicit_run;
  double explicit_error = std::numeric_limits<double>::infinity();
  for (double tol = 10.0; tol >= 1e-6; tol /= std::sqrt(10.0)) {
    explicit_params = withIntegrator(IntegratorKind::kDormandPrince, tol, 0.0);
    explicit_run = timedRun(sc, explicit_params, sim_s, repeat);
    explicit_error = maxError(explicit_run, ref);
    if (explicit_error <= implicit_error) break;
  }

  const double realtime_factor = sim_s / implicit.wall_s;
  const long implicit_rhs = implicit.stats.rhs_evals + implicit.stats.jacobian_evals;
  const long explicit_rhs = explicit_run.stats.rhs_evals;
  const double work_ratio = explicit_run.wall_s / implicit.wall_s;
  const double rhs_ratio = static_cast<double>(explicit_rhs) / static_cast<double>(implicit_rhs);

  std::printf("bench: thermo: realtime_factor=%.0f implicit_rhs_evals=%ld explicit_rhs_evals=%ld work_ratio=%.2f "
              "scenario=%s\n",
              realtime_factor, implicit_rhs, explicit_rhs, work_ratio, scenarioName(sc));
  const bool met = realtime_factor >= 1000.0;
  std::printf("bench: thermo: scenario=%s rhs_ratio=%.2f implicit_error_pa=%.3g explicit_error_pa=%.3g explicit_abs_tol_pa=%g "
              "step_us=%.2f integrator=%s abs_tol_pa=%g explicit_steps=%ld accepted=%ld rejected=%ld "
              "implicit_only_realtime_factor=%.0f implicit_only_error_pa=%.3g %s_realtime_factor=%.0f %s_error_pa=%.3g "
              "ref_uncertainty_pa=%.2g target=1000 met=%s\n",
              scenarioName(sc), rhs_ratio, implicit_error, explicit_error, explicit_params.step_control.abs_tol,
              implicit.wall_s / (sim_s * 1e9 / kExchangeNs) * 1e6, integrator.c_str(), abs_tol,
              implicit.stats.explicit_steps, implicit.stats.accepted_steps, implicit.stats.rejected_steps,
              sim_s / implicit_only.wall_s, maxError(implicit_only, ref), other_name, sim_s / other.wall_s, other_name,
              maxError(other, ref), ref_uncertainty_pa, met ? "true" : "false");

  const json report = {
      {"scenario", scenarioName(sc)},
      {"sim_s", sim_s},
      {"exchange_period_ms", kExchangeNs * 1e-6},
      {"repeat", repeat},
      {"realtime_factor", realtime_factor},
      {"target_realtime_factor", 1000.0},
      {"met", met},
      {"work_ratio", work_ratio},
      {"rhs_ratio", rhs_ratio},
      {"reference", {{"integrator", "rodas3"}, {"abs_tol_pa", 1e-7}, {"uncertainty_pa", ref_uncertainty_pa}}},
      {"implicit", describe(integrator.c_str(), implicit_params, implicit, implicit_error)},
      {"implicit_only", describe("ros2_all_implicit", implicit_only_params, implicit_only, maxError(implicit_only, ref))},
      {"other_rosenbrock", describe(other_name, other_params, other, maxError(other, ref))},
      {"explicit", describe("dormand_prince", explicit_params, explicit_run, explicit_error)},
  };
  return report;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-bench-thermo: the thermo model alone"};
  std::string out_path;
  Options o;
  app.add_option("--out", out_path, "write the JSON report here");
  app.add_option("--sim-s", o.sim_s, "simulated seconds per run")->check(CLI::PositiveNumber);
  app.add_option("--repeat", o.repeat, "runs; the best counts")->check(CLI::PositiveNumber);
  app.add_option("--abs-tol", o.abs_tol, "integrator tolerance [Pa]")->check(CLI::PositiveNumber);
  app.add_option("--integrator", o.integrator, "ros2 or rodas3")->check(CLI::IsMember({"ros2", "rodas3"}));
  return guardedMain(app, argc, argv, "bench-thermo", [&]() -> int {
  const json moving = benchScenario(Scenario::kMovingValves, o);
  const json controller = benchScenario(Scenario::kControllerLike, o);
  const json report = {{"name", "thermo"},
                       {"realtime_factor", moving["realtime_factor"]},
                       {"met", moving["met"].get<bool>() && controller["met"].get<bool>()},
                       {"work_ratio", moving["work_ratio"]},
                       {"implicit_rhs_evals", moving["implicit"]["rhs_evals"]},
                       {"explicit_rhs_evals", moving["explicit"]["rhs_evals"]},
                       {"scenarios", {moving, controller}}};

  if (!out_path.empty()) {
    std::ofstream f(out_path);
    if (!f) {
      throw ConfigError("--out = '" + out_path + "': cannot write it");
    }
    f << report.dump(2) << "\n";
  }
  return kExitOk;
  });
}
