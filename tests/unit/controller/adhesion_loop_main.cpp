// climbsim-adhesion-loop: the reference controller in a closed loop with the real thermo model
// (no DDS), printing every period's measurement and the controller's valve commands as
// hexadecimal floats (exact). The Python port's test
// (services/controller/examples/python/test_adhesion_controller.py) feeds it the same
// measurements and asserts the same commands, bit for bit.
//
// Usage: climbsim-adhesion-loop ROBOT_YAML CASE DURATION_S
//   CASE: upper-strips  the crack under the upper strips of crack-upper-strips from 1 s (several
//                       leaks flood the reservoir together: step 2b gives chambers up)
//         crack         a 25 cm² crack under chamber 1's outer strip from 1 s to 6 s
//         set-point     no leak; F* 2200 N, 12 kN from 2 s (out of reach), 1500 N from 5 s
// Each line: t_ns, the 8 pressures [Pa], F [N], P_F x, y [m], F* [N], then the 7 commands.

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "adhesion_controller.hpp"
#include "params_from_robot.hpp"
#include "thermo_model.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  if (argc != 4) {
    std::fprintf(stderr, "usage: climbsim-adhesion-loop ROBOT_YAML upper-strips|crack|set-point DURATION_S\n");
    return 2;
  }
  const std::string which = argv[2];
  if (which != "upper-strips" && which != "crack" && which != "set-point") {
    std::fprintf(stderr, "climbsim-adhesion-loop: case = %s (upper-strips, crack or set-point)\n", argv[2]);
    return 2;
  }
  const double duration_s = std::atof(argv[3]);
  const auto robot = loadRobotDescription(argv[1]);
  const auto geometry = computeGeometry(robot);
  const auto tp = thermo::thermoParamsFromRobot(robot, geometry);
  const controller::AdhesionController controller(controller::adhesionControllerParamsFromRobot(robot, geometry));
  auto control = controller.initialState();
  thermo::ThermoModel model(tp);
  auto state = model.initialState(0);
  const auto names = thermo::segmentNames(geometry);
  const auto basic = thermo::basicLeakAreas(robot, geometry);
  const auto segment = [&](const char* name) {
    for (std::size_t s = 0; s < names.size(); ++s) {
      if (names[s] == name) return s;
    }
    std::fprintf(stderr, "climbsim-adhesion-loop: no segment %s\n", name);
    std::exit(2);
  };
  thermo::ThermoInputs inputs;
  inputs.leak_area_m2 = basic;
  inputs.valve_command.assign(static_cast<std::size_t>(tp.valveCount()), 0.0);
  inputs.engines.assign(tp.engines.size(), thermo::EngineCommand{true, 1.0});
  controller::AdhesionMeasurement m;
  m.pressure_pa.assign(controller.params().chamber_area_m2.size() + 1, robot.gas.ambient_pressure_pa);
  constexpr std::int64_t kPeriodNs = 5'000'000;
  const long steps = static_cast<long>(duration_s / 5e-3 + 0.5);
  for (long k = 0; k < steps; ++k) {
    const double t_s = k * 5e-3;
    if (which == "upper-strips" && k == 200) {
      inputs.leak_area_m2[segment("outer3")] = 6e-4;
      inputs.leak_area_m2[segment("outer5")] = 6e-4;
      inputs.leak_area_m2[segment("radial3_4")] = 2e-4;
      inputs.leak_area_m2[segment("radial4_5")] = 2e-4;
    } else if (which == "crack" && (k == 200 || k == 1200)) {
      inputs.leak_area_m2[segment("outer1")] = k == 200 ? 25e-4 : basic[segment("outer1")];
    } else if (which == "set-point") {
      controller.setDesiredDownforce(control, t_s < 2.0 ? 2200.0 : t_s < 5.0 ? 12000.0 : 1500.0);
    }
    const auto out = controller.step(control, m, k * kPeriodNs, kPeriodNs);
    std::printf("%ld", static_cast<long>(k * kPeriodNs));
    for (double p : m.pressure_pa) std::printf(" %a", p);
    std::printf(" %a %a %a %a", m.downforce_n, m.p_RobotPF_m[0], m.p_RobotPF_m[1], control.desired_downforce_n);
    for (double u : out.valve_opening) std::printf(" %a", u);
    std::printf("\n");
    for (std::size_t i = 0; i < out.valve_opening.size(); ++i) inputs.valve_command[i] = out.valve_opening[i];
    const auto plant = model.step(state, inputs, k * kPeriodNs, kPeriodNs);
    for (std::size_t v = 0; v < plant.pressure_pa.size() && v < m.pressure_pa.size(); ++v) m.pressure_pa[v] = plant.pressure_pa[v];
    m.downforce_n = plant.downforce_n;
    m.p_RobotPF_m = plant.p_RobotPF_m;
  }
  return 0;
}
