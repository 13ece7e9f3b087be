/// climbsim-bench-drive: the drive model alone (no DDS) at 1 kHz substeps on the default
/// robot, driving a square on a vertical wall with 2200 N adhesion, with each force backend
/// (DriveParams::contact_backend) in the same run. Prints
///   bench: drive: realtime_factor=<simulated s per wall s, direct backend> target=50
///     met=<true|false> realtime_factor_simbody_contact=<the same, Simbody-contact backend>
///     direct_over_simbody_contact=<ratio> ...
/// and writes the same as JSON to --out. The backends run alternately --repeat times and each
/// reports its best run (the one least disturbed by other processes). The same runs also give
/// the factors per second of the process' CPU time (*_cpu: on a shared machine the wall-clock
/// factor also counts the time the process waited for a core), and as a yardstick it times
/// Simbody's bare realize cycle for a single free body (simbody_floor_us), the cost below
/// which no Simbody model of this machine can step. With --scene (the generated pylon,
/// $BUILD/scenes/pylon.xml) the direct backend also drives the square from --x-m, --y-m on the
/// scene's surface enveloped over the tyre patch (wall.wheels_on: surface), and the line adds
///   realtime_factor_surface=.. step_ms=<direct, per 5 ms step> step_ms_surface=<on the surface>
/// With --surface-only it drives only on the scene's surface and prints
///   bench: drive: surface_only realtime_factor_surface=.. step_ms_surface=..
/// (the case the e2e run steps, alone: for a profiler such as callgrind).

#include <Simbody.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "drive_model.hpp"
#include "params_from_robot.hpp"
#include "wheels_over_scene.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

/// CPU time of this process so far [s].
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Wall time per substep [µs] of the semi-implicit Euler loop on one free body under gravity.
double simbodyFloorMicros(int substeps) {
  using namespace SimTK;
  MultibodySystem system;
  SimbodyMatterSubsystem matter(system);
  GeneralForceSubsystem forces(system);
  Force::UniformGravity(forces, matter, Vec3(0, -9.81, 0));
  Body::Rigid body(MassProperties(45.0, Vec3(0), Inertia(2.0)));
  MobilizedBody::Free free(matter.Ground(), Transform(), body, Transform());
  State state = system.realizeTopology();
  Vector qdot;
  const auto start = Clock::now();
  for (int k = 0; k < substeps; ++k) {
    system.realize(state, Stage::Acceleration);
    state.updU() += 1e-3 * state.getUDot();
    matter.multiplyByN(state, false, state.getU(), qdot);
    state.updQ() += 1e-3 * qdot;
    system.realize(state, Stage::Velocity);
  }
  return seconds(Clock::now() - start) / substeps * 1e6;
}

/// One backend's best run.
struct Measured {
  double rtf = 0.0;         ///< simulated s per wall s
  double rtf_cpu = 0.0;     ///< simulated s per CPU s
  double wall_s = 0.0;      ///< of the run with the best rtf
  double cpu_s = 0.0;       ///< of the run with the best rtf_cpu
  double substep_us = 0.0;  ///< wall time per substep of the run with the best rtf
  std::int64_t substeps = 0;
  bool fell = false;
};

/// Drives the square for `sim_s` simulated seconds; keeps the better factors in `best`.
void run(const climbsim::drive::DriveParams& params, double sim_s, Measured& best,
         const climbsim::drive::StartPose& start_pose = {}) {
  using namespace climbsim;
  const drive::DriveModel model(params, drive::WallOrientation::vertical());
  drive::DriveModelState state = model.initialState(start_pose);
  constexpr std::int64_t kStepNs = 5'000'000;
  const auto steps = static_cast<std::int64_t>(sim_s * 1e9 / kStepNs);
  drive::DriveInputs in;
  in.downforce_n = 2200.0;
  const auto start = Clock::now();
  const double cpu_start = cpuSeconds();
  for (std::int64_t k = 0; k < steps; ++k) {
    // A square of 4 s legs, so that steering, rolling and slipping are all exercised.
    const int leg = static_cast<int>((k * kStepNs / 4'000'000'000LL) % 4);
    const double vx[4] = {0.0, -0.05, 0.0, 0.05};
    const double vy[4] = {0.05, 0.0, -0.05, 0.0};
    in.command.vx_mps = vx[leg];
    in.command.vy_mps = vy[leg];
    model.step(state, in, k * kStepNs, kStepNs);
  }
  const double wall_s = seconds(Clock::now() - start);
  const double cpu_s = cpuSeconds() - cpu_start;
  const double simulated_s = static_cast<double>(steps * kStepNs) * 1e-9;
  if (simulated_s / wall_s > best.rtf) {
    best.rtf = simulated_s / wall_s;
    best.wall_s = wall_s;
    best.substep_us = wall_s / static_cast<double>(state.substeps()) * 1e6;
  }
  if (simulated_s / cpu_s > best.rtf_cpu) {
    best.rtf_cpu = simulated_s / cpu_s;
    best.cpu_s = cpu_s;
  }
  best.substeps = state.substeps();
  best.fell = best.fell || state.outputs().fell;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-bench-drive: real-time factor of the drive model at 1 kHz, both force backends"};
  std::string out_file;
  double sim_s = 20.0;
  double substep_hz = 1000.0;
  int repeat = 3;
  app.add_option("--out", out_file, "write the results as JSON to this file")->required();
  app.add_option("--sim-s", sim_s, "simulated seconds per run (> 0)");
  app.add_option("--substep-hz", substep_hz, "model integration rate [Hz]");
  app.add_option("--repeat", repeat, "runs per backend, alternating; the best counts (1..100)");
  std::string scene_file;
  drive::StartPose surface_start;
  surface_start.x_m = 1.0, surface_start.y_m = 1.2;
  app.add_option("--scene", scene_file, "also drive on this scene's surface (the direct backend)");
  app.add_option("--x-m", surface_start.x_m, "start on the scene, W's x [m]");
  app.add_option("--y-m", surface_start.y_m, "start on the scene, W's y [m]");
  bool surface_only = false;
  app.add_flag("--surface-only", surface_only, "only the run on --scene's surface (for a profiler)");
  return guardedMain(app, argc, argv, "bench-drive", [&]() -> int {
    if (!(sim_s > 0.0 && sim_s <= 3600.0)) throw ConfigError("--sim-s = " + std::to_string(sim_s) + ": must be in (0, 3600]");
    if (!(substep_hz >= 100.0 && substep_hz <= 100000.0)) {
      throw ConfigError("--substep-hz = " + std::to_string(substep_hz) + ": must be in [100, 100000]");
    }
    if (!(repeat >= 1 && repeat <= 100)) throw ConfigError("--repeat = " + std::to_string(repeat) + ": must be in [1, 100]");
    const auto robot = loadRobotDescription(CLIMBSIM_DEFAULT_ROBOT_FILE);
    auto direct_params = drive::driveParamsFromRobot(robot, computeGeometry(robot));
    direct_params.substep_s = 1.0 / substep_hz;
    direct_params.contact_backend = drive::ContactBackend::kDirect;
    auto simbody_params = direct_params;
    simbody_params.contact_backend = drive::ContactBackend::kSimbody;
    auto surface_params = direct_params;
    if (!scene_file.empty()) {
      surface_params.ground =
          drive::wheelGroundOfScene(drive::loadWheelSceneInBackground(scene_file), surface_params.tyre_patch_m);
    }
    Measured direct, simbody, surface;
    if (surface_only) {
      if (!surface_params.ground) throw ConfigError("--surface-only needs --scene");
      for (int r = 0; r < repeat; ++r) run(surface_params, sim_s, surface, surface_start);
      const double step_ms = 1e-3 * surface.substep_us * 0.005 * substep_hz;
      std::printf("bench: drive: surface_only realtime_factor_surface=%.1f step_ms_surface=%.3f fell_surface=%s\n",
                  surface.rtf, step_ms, surface.fell ? "true" : "false");
      std::ofstream out(out_file, std::ios::trunc);
      if (!out) throw ConfigError("--out = '" + out_file + "': cannot write it");
      out << nlohmann::json{{"name", "drive"}, {"realtime_factor_surface", surface.rtf}, {"step_ms_surface", step_ms},
                            {"fell_surface", surface.fell}}.dump(2) << '\n';
      return kExitOk;
    }
    for (int r = 0; r < repeat; ++r) {
      run(direct_params, sim_s, direct);
      run(simbody_params, sim_s, simbody);
      if (surface_params.ground) run(surface_params, sim_s, surface, surface_start);
    }
    const double substeps_per_step = 0.005 * substep_hz;
    const double simulated_s = static_cast<double>(static_cast<std::int64_t>(sim_s * 1e9 / 5'000'000) * 5'000'000) * 1e-9;
    const double ratio = direct.rtf / simbody.rtf;
    const double ratio_cpu = direct.rtf_cpu / simbody.rtf_cpu;
    const double floor_us = simbodyFloorMicros(20000);
    const bool met = direct.rtf >= 50.0;
    std::printf(
        "bench: drive: realtime_factor=%.1f target=50 met=%s realtime_factor_simbody_contact=%.1f "
        "direct_over_simbody_contact=%.2f realtime_factor_cpu=%.1f realtime_factor_simbody_contact_cpu=%.1f "
        "direct_over_simbody_contact_cpu=%.2f substep_hz=%.0f substep_us=%.1f simbody_contact_substep_us=%.1f "
        "simbody_floor_us=%.1f model_over_floor=%.2f repeat=%d fell=%s step_ms=%.3f",
        direct.rtf, met ? "true" : "false", simbody.rtf, ratio, direct.rtf_cpu, simbody.rtf_cpu, ratio_cpu, substep_hz,
        direct.substep_us, simbody.substep_us, floor_us, direct.substep_us / floor_us, repeat,
        direct.fell || simbody.fell ? "true" : "false", 1e-3 * direct.substep_us * substeps_per_step);
    if (surface_params.ground) {
      std::printf(" realtime_factor_surface=%.1f step_ms_surface=%.3f fell_surface=%s", surface.rtf,
                  1e-3 * surface.substep_us * substeps_per_step, surface.fell ? "true" : "false");
    }
    std::printf("\n");
    nlohmann::json j = {{"name", "drive"},
                        {"realtime_factor", direct.rtf},
                        {"target", 50.0},
                        {"met", met},
                        {"realtime_factor_simbody_contact", simbody.rtf},
                        {"direct_over_simbody_contact", ratio},
                        {"realtime_factor_cpu", direct.rtf_cpu},
                        {"realtime_factor_simbody_contact_cpu", simbody.rtf_cpu},
                        {"direct_over_simbody_contact_cpu", ratio_cpu},
                        {"substep_hz", substep_hz},
                        {"simulated_s", simulated_s},
                        {"repeat", repeat},
                        {"wall_s", direct.wall_s},
                        {"cpu_s", direct.cpu_s},
                        {"simbody_contact_wall_s", simbody.wall_s},
                        {"simbody_contact_cpu_s", simbody.cpu_s},
                        {"substeps", direct.substeps},
                        {"substep_us", direct.substep_us},
                        {"simbody_contact_substep_us", simbody.substep_us},
                        {"simbody_floor_us", floor_us},
                        {"model_over_floor", direct.substep_us / floor_us},
                        {"fell", direct.fell || simbody.fell},
                        {"step_ms", 1e-3 * direct.substep_us * substeps_per_step}};
    if (surface_params.ground) {
      j["realtime_factor_surface"] = surface.rtf;
      j["step_ms_surface"] = 1e-3 * surface.substep_us * substeps_per_step;
      j["fell_surface"] = surface.fell;
    }
    std::ofstream out(out_file, std::ios::trunc);
    if (!out) throw ConfigError("--out = '" + out_file + "': cannot write it");
    out << j.dump(2) << '\n';
    return kExitOk;
  });
}
