// thermoParamsFromRobot(deploy/robots/cromsci.yaml) against the hand-typed default robot.

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"
#include "thermo_cromsci_params.hpp"

namespace climbsim::thermo {
namespace {

constexpr double kTol = 1e-12;

struct Loaded {
  RobotDescription robot;
  RobotGeometry geometry;
};

Loaded loadCromsci() {
  Loaded l;
  l.robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
  l.geometry = computeGeometry(l.robot);
  return l;
}

TEST(ThermoParamsFromRobot, CromsciEqualsTheHandTypedDefaultsInEveryField) {
  const auto l = loadCromsci();
  const ThermoParams got = thermoParamsFromRobot(l.robot, l.geometry);
  const ThermoParams want = testing::defaultCromsciParams();

  EXPECT_EQ(got.gas.ambient_pressure_pa, want.gas.ambient_pressure_pa);
  EXPECT_EQ(got.gas.kappa, want.gas.kappa);
  EXPECT_EQ(got.gas.gas_constant_jpkgk, want.gas.gas_constant_jpkgk);
  EXPECT_EQ(got.gas.temperature_k, want.gas.temperature_k);
  EXPECT_EQ(got.gas.orifice_density_kgpm3, want.gas.orifice_density_kgpm3);
  ASSERT_EQ(got.chamberCount(), want.chamberCount());
  EXPECT_EQ(got.has_reservoir, want.has_reservoir);
  for (int i = 0; i < want.chamberCount(); ++i) {
    EXPECT_NEAR(got.chamber_volume_m3[i], want.chamber_volume_m3[i], kTol) << "chamber " << i + 1;
    EXPECT_NEAR(got.chamber_area_m2[i], want.chamber_area_m2[i], kTol) << "chamber " << i + 1;
    EXPECT_NEAR(got.p_RobotChamber_m[i][0], want.p_RobotChamber_m[i][0], kTol) << "chamber " << i + 1;
    EXPECT_NEAR(got.p_RobotChamber_m[i][1], want.p_RobotChamber_m[i][1], kTol) << "chamber " << i + 1;
  }
  EXPECT_NEAR(got.reservoir_volume_m3, want.reservoir_volume_m3, kTol);
  // Same segment order as the geometry (outer, radial, inner), so no mapping by name is needed.
  ASSERT_EQ(got.segments.size(), want.segments.size());
  for (std::size_t s = 0; s < got.segments.size(); ++s) {
    EXPECT_EQ(got.segments[s].volume_a, want.segments[s].volume_a) << l.geometry.segments[s].name;
    EXPECT_EQ(got.segments[s].volume_b, want.segments[s].volume_b) << l.geometry.segments[s].name;
  }
  ASSERT_EQ(got.engines.size(), want.engines.size());
  for (std::size_t e = 0; e < got.engines.size(); ++e) {
    EXPECT_EQ(got.engines[e].pressure_rise_max_pa, want.engines[e].pressure_rise_max_pa);
    EXPECT_EQ(got.engines[e].volume_flow_max_m3ps, want.engines[e].volume_flow_max_m3ps);
    EXPECT_EQ(got.engines[e].speed_lag_s, want.engines[e].speed_lag_s);
    EXPECT_EQ(got.engines[e].chamber, SuctionEngineParams::kPumpsReservoir);
  }
  EXPECT_EQ(got.valve.max_area_m2, want.valve.max_area_m2);
  EXPECT_EQ(got.valve.discharge_coefficient, want.valve.discharge_coefficient);
  EXPECT_EQ(got.valve.full_stroke_s, want.valve.full_stroke_s);
  EXPECT_EQ(got.valve.command_delay_s, want.valve.command_delay_s);
  EXPECT_EQ(got.laminar_threshold_pa, want.laminar_threshold_pa);
  EXPECT_EQ(got.integrator, want.integrator);
  EXPECT_EQ(got.initial_step_s, want.initial_step_s);
}

TEST(ThermoParamsFromRobot, BasicLeakAreasAndNamesFollowTheSegmentOrder) {
  const auto l = loadCromsci();
  const auto areas = basicLeakAreas(l.robot, l.geometry);
  const auto want = testing::basicLeakAreas();
  ASSERT_EQ(areas.size(), want.size());
  for (std::size_t s = 0; s < areas.size(); ++s) EXPECT_NEAR(areas[s], want[s], kTol) << s;
  const auto names = segmentNames(l.geometry);
  ASSERT_EQ(names.size(), 18u);
  EXPECT_EQ(names[0], "outer1");
  EXPECT_EQ(names[11], "radial6_1");
  EXPECT_EQ(names[17], "inner6");
}

}  // namespace
}  // namespace climbsim::thermo
