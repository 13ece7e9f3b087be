// climbsim-engine-loop: the engine law (robots without a reservoir) in a closed loop with the
// real thermo model (no DDS), printing every period's measurement and the law's engine speeds
// as hexadecimal floats (exact). The Python port's test
// (services/controller/examples/python/test_adhesion_controller.py) feeds it the same
// measurements and asserts the same speeds, bit for bit.
//
// Usage: climbsim-engine-loop ROBOT_YAML SET_POINT_N DURATION_S
//   The robot's basic leaks; from 2 s to 5 s the outer strips of chamber 1 leak 6 times as much
//   (an engine at full speed, the balance trims held or moving), then the basic leaks again.
// Each line: t_ns, the N pressures [Pa], F [N], P_F x, y [m], then the speeds of the engines.

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine_controller.hpp"
#include "params_from_robot.hpp"
#include "thermo_model.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  if (argc != 4) {
    std::fprintf(stderr, "usage: climbsim-engine-loop ROBOT_YAML SET_POINT_N DURATION_S\n");
    return 2;
  }
  const auto robot = loadRobotDescription(argv[1]);
  const auto geometry = computeGeometry(robot);
  const auto tp = thermo::thermoParamsFromRobot(robot, geometry);
  auto params = controller::engineControllerParamsFromRobot(robot, geometry);
  params.desired_downforce_n = std::atof(argv[2]);
  const controller::EngineController controller(params);
  auto control = controller.initialState();
  thermo::ThermoModel model(tp);
  auto state = model.initialState(0);
  const auto basic = thermo::basicLeakAreas(robot, geometry);
  thermo::ThermoInputs inputs;
  inputs.leak_area_m2 = basic;
  inputs.engines.assign(tp.engines.size(), thermo::EngineCommand{false, 1.0});
  controller::AdhesionMeasurement m;
  m.pressure_pa.assign(geometry.chambers.size(), robot.gas.ambient_pressure_pa);
  constexpr std::int64_t kPeriodNs = 5'000'000;
  const long steps = static_cast<long>(std::atof(argv[3]) / 5e-3 + 0.5);
  for (long k = 0; k < steps; ++k) {
    if (k == 400 || k == 1000) {
      for (std::size_t s = 0; s < geometry.segments.size(); ++s) {
        if (geometry.segments[s].volume_a == 0 && geometry.segments[s].volume_b == kAmbient) {
          inputs.leak_area_m2[s] = k == 400 ? 6.0 * basic[s] : basic[s];
        }
      }
    }
    const auto out = controller.step(control, m, k * kPeriodNs, kPeriodNs);
    std::printf("%ld", static_cast<long>(k * kPeriodNs));
    for (double p : m.pressure_pa) std::printf(" %a", p);
    std::printf(" %a %a %a", m.downforce_n, m.p_RobotPF_m[0], m.p_RobotPF_m[1]);
    for (double w : out.engine_speed) std::printf(" %a", w);
    std::printf("\n");
    for (std::size_t e = 0; e < out.engine_speed.size(); ++e) inputs.engines[e] = thermo::EngineCommand{true, out.engine_speed[e]};
    const auto plant = model.step(state, inputs, k * kPeriodNs, kPeriodNs);
    m.pressure_pa = plant.pressure_pa;
    m.downforce_n = plant.downforce_n;
    m.p_RobotPF_m = plant.p_RobotPF_m;
  }
  return 0;
}
