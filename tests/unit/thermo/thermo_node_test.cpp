// The thermo node without a network: translators, the leakage merger, input holding.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"
#include "thermo_node.hpp"
#include "thermo_translate.hpp"

namespace climbsim::thermo {
namespace {

constexpr std::int64_t kPeriodNs = 5'000'000;

struct Robot {
  RobotDescription description;
  RobotGeometry geometry;
  ThermoParams params;
  std::vector<std::string> names;
  std::vector<double> basic;
};

const Robot& cromsci() {
  static const Robot robot = [] {
    Robot r;
    r.description = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
    r.geometry = computeGeometry(r.description);
    r.params = thermoParamsFromRobot(r.description, r.geometry);
    r.names = segmentNames(r.geometry);
    r.basic = basicLeakAreas(r.description, r.geometry);
    return r;
  }();
  return robot;
}

std::vector<std::size_t> range(std::size_t from, std::size_t to) {
  std::vector<std::size_t> out;
  for (std::size_t i = from; i < to; ++i) out.push_back(i);
  return out;
}

climbsim::Leakage part(const std::string& source, const std::vector<double>& areas,
                       const std::vector<std::size_t>& indices) {
  const auto& r = cromsci();
  auto sample = leakageToIdl(r.names, areas, std::vector<double>(areas.size(), 1e-4), indices);
  sample.source(source);
  return sample;
}

/// Distinct areas per segment, so that a misplaced value shows.
std::vector<double> rampAreas() {
  std::vector<double> a;
  for (std::size_t i = 0; i < cromsci().names.size(); ++i) a.push_back(1e-6 * static_cast<double>(i + 1));
  return a;
}

bool bitEqual(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(ThermoTranslate, ValveAndEngineCommandsRoundTrip) {
  const std::vector<double> opening{0.0, 0.125, 0.25, 0.5, 0.75, 0.875, 1.0};
  EXPECT_EQ(valveCommandFromIdl(valveCommandToIdl(opening)), opening);
  EXPECT_THROW(valveCommandToIdl(std::vector<double>(kMaxChambers + 1)), std::invalid_argument);
  const std::vector<EngineCommand> engines{{true, 1.0}, {false, 0.5}, {true, 0.25}};
  const auto back = engineCommandsFromIdl(engineCommandToIdl(engines));
  ASSERT_EQ(back.size(), engines.size());
  for (std::size_t e = 0; e < engines.size(); ++e) {
    EXPECT_EQ(back[e].on, engines[e].on);
    EXPECT_EQ(back[e].speed, engines[e].speed);
  }
  EXPECT_THROW(engineCommandToIdl(std::vector<EngineCommand>(kMaxEngines + 1)), std::invalid_argument);
}

TEST(ThermoTranslate, OutputsRoundTripThroughChamberStateAndAdhesionForce) {
  const auto& r = cromsci();
  const ThermoModel model(r.params);
  ThermoState state = model.initialState(0);
  ThermoInputs in;
  in.leak_area_m2 = r.basic;
  in.valve_command.assign(7, 1.0);
  in.engines.assign(r.params.engines.size(), EngineCommand{true, 1.0});
  ThermoOutputs out;
  for (int k = 0; k < 100; ++k) out = model.step(state, in, state.t_ns, kPeriodNs);
  ASSERT_GT(out.downforce_n, 0.0);
  const auto back = outputsFromIdl(chamberStateToIdl(out), adhesionForceToIdl(out));
  EXPECT_EQ(back.pressure_pa, out.pressure_pa);
  EXPECT_EQ(back.valve_opening, out.valve_opening);
  EXPECT_EQ(back.engine_speed, out.engine_speed);
  EXPECT_EQ(back.segment_mass_flow_kgps, out.segment_mass_flow_kgps);
  EXPECT_EQ(back.downforce_n, out.downforce_n);
  EXPECT_EQ(back.p_RobotPF_m, out.p_RobotPF_m);
}

TEST(LeakageMerger, TwoShardsGiveTheUnshardedAreasBitForBit) {
  const auto& r = cromsci();
  const auto areas = rampAreas();
  LeakageMerger whole(r.names, r.basic);
  LeakageMerger sharded(r.names, r.basic);
  whole.merge({part("sealing", areas, range(0, 18))});
  sharded.merge({part("sealing-a", areas, {0, 2, 4, 6, 8, 10, 12, 14, 16}),
                 part("sealing-b", areas, {1, 3, 5, 7, 9, 11, 13, 15, 17})});
  EXPECT_TRUE(bitEqual(whole.leakAreas(), areas));
  EXPECT_TRUE(bitEqual(sharded.leakAreas(), whole.leakAreas()));
  EXPECT_EQ(whole.dropped(), 0u);
  EXPECT_EQ(sharded.dropped(), 0u);
}

TEST(LeakageMerger, SegmentsNoPartCoversKeepTheirLastValidArea) {
  const auto& r = cromsci();
  LeakageMerger merger(r.names, r.basic);
  const auto areas = rampAreas();
  merger.merge({part("a", areas, range(0, 6))});
  auto want = r.basic;
  for (std::size_t i = 0; i < 6; ++i) want[i] = areas[i];
  EXPECT_TRUE(bitEqual(merger.leakAreas(), want));
  merger.merge({});
  EXPECT_TRUE(bitEqual(merger.leakAreas(), want));
}

TEST(LeakageMerger, BadPartsAreDroppedCountedAndTheLastValidAreasHeld) {
  const auto& r = cromsci();
  LeakageMerger merger(r.names, r.basic);
  const auto good = rampAreas();
  merger.merge({part("a", good, range(0, 18))});

  auto nan_areas = good;
  nan_areas[3] = std::numeric_limits<double>::quiet_NaN();
  auto negative = good;
  negative[4] = -1e-6;
  auto infinite = good;
  infinite[5] = std::numeric_limits<double>::infinity();
  auto unknown = part("a", good, {0, 1});
  unknown.segments()[1].segment("outer9");
  const auto twice = part("a", good, {0, 1, 0});

  std::uint64_t expected = 0;
  for (const auto& bad : {part("a", nan_areas, range(0, 18)), part("a", negative, range(0, 18)),
                          part("a", infinite, range(0, 18)), unknown, twice}) {
    EXPECT_NE(merger.check(bad), "");
    merger.merge({bad});
    EXPECT_EQ(merger.dropped(), ++expected);
    EXPECT_TRUE(bitEqual(merger.leakAreas(), good));
  }
  EXPECT_NE(merger.check(unknown).find("outer9"), std::string::npos) << merger.check(unknown);
  EXPECT_NE(merger.check(twice).find("given twice"), std::string::npos) << merger.check(twice);

  // A bad shard does not spoil a good one; an overlap drops the later part.
  auto other = good;
  for (double& a : other) a *= 2.0;
  auto nan_late = good;
  nan_late[12] = std::numeric_limits<double>::quiet_NaN();
  merger.merge({part("a", other, range(0, 9)), part("b", nan_late, range(9, 18))});
  EXPECT_EQ(merger.dropped(), ++expected);
  auto want = good;
  for (std::size_t i = 0; i < 9; ++i) want[i] = other[i];
  EXPECT_TRUE(bitEqual(merger.leakAreas(), want));
  merger.merge({part("a", good, range(0, 10)), part("b", other, range(9, 18))});
  EXPECT_EQ(merger.dropped(), ++expected);
  for (std::size_t i = 0; i < 10; ++i) want[i] = good[i];
  EXPECT_TRUE(bitEqual(merger.leakAreas(), want));
}

/// One opening for each of cromsci's seven valves.
std::vector<double> allValves(double opening) { return std::vector<double>(7, opening); }

TEST(ThermoNode, BadCommandsAreDroppedAndTheLastValidOnesHeld) {
  const auto& r = cromsci();
  ThermoNode node(r.params, r.names, r.basic);
  EXPECT_TRUE(bitEqual(node.heldInputs().leak_area_m2, r.basic));
  for (double v : node.heldInputs().valve_command) EXPECT_EQ(v, 0.0);
  for (const auto& e : node.heldInputs().engines) EXPECT_FALSE(e.on);

  const std::vector<double> open = allValves(0.5);
  auto valves = valveCommandToIdl(open);
  auto engines = engineCommandToIdl(std::vector<EngineCommand>(3, EngineCommand{true, 1.0}));
  node.step(0, kPeriodNs, {}, {valves}, {engines});
  EXPECT_EQ(node.heldInputs().valve_command, open);
  EXPECT_TRUE(node.heldInputs().engines[2].on);

  auto bad_valves = valves;
  bad_valves.opening()[2] = 1.5;
  auto nan_valves = valves;
  nan_valves.opening()[0] = std::numeric_limits<double>::quiet_NaN();
  auto too_few = engineCommandToIdl(std::vector<EngineCommand>(2, EngineCommand{false, 1.0}));
  auto bad_speed = engineCommandToIdl(std::vector<EngineCommand>(3, EngineCommand{false, -0.1}));
  auto other_robot = valves;
  other_robot.opening().resize(4, 0.5);  // sized for another robot: refused, not read past its end
  node.step(kPeriodNs, kPeriodNs, {}, {bad_valves, nan_valves, other_robot}, {too_few, bad_speed});
  EXPECT_EQ(node.droppedValveCommands(), 3u);
  EXPECT_EQ(node.droppedEngineCommands(), 2u);
  EXPECT_EQ(node.heldInputs().valve_command, open);
  for (const auto& e : node.heldInputs().engines) EXPECT_TRUE(e.on);
}

TEST(ThermoNode, TheControllersSetPointIsHeldAndABadOneDropsItsCommand) {
  const auto& r = cromsci();
  ThermoNode node(r.params, r.names, r.basic);
  EXPECT_EQ(node.downforceSetpoint(), 0.0) << "none stated before any command";
  const std::vector<double> open = allValves(0.5);
  auto valves = valveCommandToIdl(open);
  valves.downforce_setpoint_n(1800.0);
  node.step(0, kPeriodNs, {}, {valves}, {});
  EXPECT_EQ(node.downforceSetpoint(), 1800.0);
  auto nan_setpoint = valveCommandToIdl(allValves(0.9));
  nan_setpoint.downforce_setpoint_n(std::numeric_limits<double>::quiet_NaN());
  auto huge_setpoint = nan_setpoint;
  huge_setpoint.downforce_setpoint_n(2e6);
  auto bad_opening = valveCommandToIdl(allValves(0.9));
  bad_opening.opening()[1] = -0.5;
  bad_opening.downforce_setpoint_n(900.0);
  node.step(kPeriodNs, kPeriodNs, {}, {nan_setpoint, huge_setpoint, bad_opening}, {});
  EXPECT_EQ(node.droppedValveCommands(), 3u);
  EXPECT_EQ(node.downforceSetpoint(), 1800.0) << "a dropped command's set-point is not taken";
  EXPECT_EQ(node.heldInputs().valve_command, open) << "nor its openings";
  // The initial state (row 0 of the trace): ambient everywhere, nothing pulls.
  ThermoNode fresh(r.params, r.names, r.basic);
  const auto initial = fresh.initialOutputs();
  for (double p : initial.pressure_pa) EXPECT_EQ(p, r.params.gas.ambient_pressure_pa);
  EXPECT_EQ(initial.downforce_n, 0.0);
  for (double v : initial.valve_opening) EXPECT_EQ(v, 0.0);
  for (double f : initial.segment_mass_flow_kgps) EXPECT_EQ(f, 0.0) << "no pressure difference, no flow";
}

TEST(ThermoNode, StepsTheModelOverThePeriodFromTheFirstDueTime) {
  const auto& r = cromsci();
  ThermoNode node(r.params, r.names, r.basic);
  // First due at an offset: the state starts there and advances one period per call.
  const auto first = node.step(3 * kPeriodNs, 2 * kPeriodNs, {}, {}, {});
  EXPECT_EQ(first.t_ns, 5 * kPeriodNs);
  const auto second = node.step(5 * kPeriodNs, 2 * kPeriodNs, {}, {}, {});
  EXPECT_EQ(second.t_ns, 7 * kPeriodNs);
  EXPECT_THROW(node.step(8 * kPeriodNs, 2 * kPeriodNs, {}, {}, {}), std::logic_error);
}

Scenario::Fault valveStuck(double t_s, int chamber, double opening) {
  Scenario::Fault f;
  f.t_s = t_s;
  f.kind = Scenario::FaultKind::kValveStuck;
  f.chamber = chamber;
  f.opening = opening;
  return f;
}

Scenario::Fault engineFailure(double t_s, int engine) {
  Scenario::Fault f;
  f.t_s = t_s;
  f.kind = Scenario::FaultKind::kEngineFailure;
  f.engine = engine;
  return f;
}

/// The robot's params with the scenario faults `faults` (plantFaultsFromScenario).
ThermoParams withFaults(ThermoParams params, const std::vector<Scenario::Fault>& faults) {
  params.faults = plantFaultsFromScenario(faults, "test", params);
  return params;
}

TEST(ThermoNodeFaults, AStuckValveGoesToItsOpeningAtTheValveRateAndStaysAgainstCommands) {
  const auto& r = cromsci();
  const int chamber = 3;
  const auto c = static_cast<std::size_t>(chamber - 1);
  const double stuck = 0.2;
  const std::int64_t fault_ns = 20 * kPeriodNs;
  ThermoNode faulty(withFaults(r.params, {valveStuck(static_cast<double>(fault_ns) * 1e-9, chamber, stuck)}), r.names,
                    r.basic);
  ThermoNode healthy(r.params, r.names, r.basic);
  const auto engines = engineCommandToIdl(std::vector<EngineCommand>(r.params.engines.size(), EngineCommand{true, 1.0}));
  const double max_move = static_cast<double>(kPeriodNs) * 1e-9 / r.params.valve.full_stroke_s;
  const double delay_s = r.params.valve.command_delay_s;

  // Open everything, then command 0.9 one period before the fault (still under way when the
  // valve sticks: it must not arrive), then close everything.
  double opening_at_fault = -1.0;
  std::int64_t landed_ns = -1;
  for (int k = 0; k < 200; ++k) {
    const std::int64_t t = k * kPeriodNs;
    const double command = t < fault_ns - kPeriodNs ? 1.0 : (t < fault_ns + 60 * kPeriodNs ? 0.9 : 0.0);
    const auto valves = valveCommandToIdl(allValves(command));
    const auto want = healthy.step(t, kPeriodNs, {}, {valves}, {engines});
    const auto got = faulty.step(t, kPeriodNs, {}, {valves}, {engines});
    // The model names the fault at the step it takes effect, and only then.
    ASSERT_EQ(got.faults_taking_effect, (t == fault_ns ? std::vector<std::size_t>{0} : std::vector<std::size_t>{}))
        << "t_ns = " << t;
    if (t + kPeriodNs <= fault_ns) {
      // Nothing has happened yet: the same plant bit for bit.
      ASSERT_EQ(got.pressure_pa, want.pressure_pa) << "t_ns = " << t;
      ASSERT_EQ(got.valve_opening, want.valve_opening) << "t_ns = " << t;
      opening_at_fault = got.valve_opening[c];
      continue;
    }
    // The other valves follow their commands untouched.
    for (std::size_t o = 0; o < got.valve_opening.size(); ++o) {
      if (o != c) {
        ASSERT_EQ(got.valve_opening[o], want.valve_opening[o]) << "chamber " << o + 1 << " t_ns = " << t;
      }
    }
    if (landed_ns < 0 && got.valve_opening[c] == stuck) landed_ns = got.t_ns;
    if (landed_ns >= 0) {
      ASSERT_EQ(got.valve_opening[c], stuck) << "left the stuck opening at t_ns = " << got.t_ns;
    }
  }
  // Before the fault the valve was opening towards 1 (well away from the stuck value).
  ASSERT_GT(opening_at_fault, stuck + 2.0 * max_move);
  // It moved at the rate limit from the fault time on, not one command delay later.
  ASSERT_GE(landed_ns, 0) << "the stuck valve never reached its opening";
  const double travel_s = (opening_at_fault - stuck) * r.params.valve.full_stroke_s;
  EXPECT_GE(static_cast<double>(landed_ns - fault_ns) * 1e-9, travel_s - 1e-9);
  EXPECT_LE(static_cast<double>(landed_ns - fault_ns) * 1e-9, travel_s + 1e-9 + 1e-9 * kPeriodNs);
  EXPECT_LT(static_cast<double>(landed_ns - fault_ns) * 1e-9, travel_s + delay_s);
  // The commands were received and held as given: the fault acts in the plant only.
  EXPECT_EQ(faulty.heldInputs().valve_command[c], 0.0);
}

TEST(ThermoNodeFaults, AFailedEngineStopsWhateverIsCommandedAndTheReservoirSuctionDrops) {
  const auto& r = cromsci();
  ASSERT_GE(r.params.engines.size(), 2u);
  const int engine = 2;
  const auto e = static_cast<std::size_t>(engine - 1);
  const std::int64_t dt = 4 * kPeriodNs;
  const double tau_s = r.params.engines[e].speed_lag_s;
  // The engines have spun up (10 lags) and the pressures settled before the fault.
  const std::int64_t fault_ns = (std::llround(10.0 * tau_s * 1e9) / dt + 1) * dt;
  const double p_o = r.params.gas.ambient_pressure_pa;
  ThermoNode faulty(withFaults(r.params, {engineFailure(static_cast<double>(fault_ns) * 1e-9, engine)}), r.names, r.basic);
  ThermoNode healthy(r.params, r.names, r.basic);
  // Every engine is commanded on at full speed for the whole run.
  const auto engines = engineCommandToIdl(std::vector<EngineCommand>(r.params.engines.size(), EngineCommand{true, 1.0}));
  const auto valves = valveCommandToIdl(allValves(1.0));

  double speed_at_fault = -1.0, suction_at_fault = 0.0;
  ThermoOutputs got, want;
  const auto steps = static_cast<int>(fault_ns / dt + std::llround(10.0 * tau_s * 1e9) / dt);
  for (int k = 0; k < steps; ++k) {
    const std::int64_t t = k * dt;
    want = healthy.step(t, dt, {}, {valves}, {engines});
    got = faulty.step(t, dt, {}, {valves}, {engines});
    if (t + dt <= fault_ns) {
      ASSERT_EQ(got.pressure_pa, want.pressure_pa) << "t_ns = " << t;
      ASSERT_EQ(got.engine_speed, want.engine_speed) << "t_ns = " << t;
      speed_at_fault = got.engine_speed[e];
      suction_at_fault = p_o - got.pressure_pa[r.params.reservoir()];
      continue;
    }
    // First-order lag towards 0 from the fault time on; the other engines run as commanded.
    const double elapsed_s = static_cast<double>(got.t_ns - fault_ns) * 1e-9;
    ASSERT_NEAR(got.engine_speed[e], speed_at_fault * std::exp(-elapsed_s / tau_s), 1e-12) << "t_ns = " << got.t_ns;
    for (std::size_t o = 0; o < got.engine_speed.size(); ++o) {
      if (o != e) {
        ASSERT_EQ(got.engine_speed[o], want.engine_speed[o]);
      }
    }
  }
  ASSERT_GT(speed_at_fault, 0.5);
  EXPECT_LT(got.engine_speed[e], 1e-3 * speed_at_fault);
  EXPECT_TRUE(faulty.heldInputs().engines[e].on);  // commanded on; the plant has it off
  // Two engines remove less air than three: the reservoir suction falls, below the healthy twin's.
  const double suction = p_o - got.pressure_pa[r.params.reservoir()];
  const double healthy_suction = p_o - want.pressure_pa[r.params.reservoir()];
  EXPECT_GT(suction, 0.0);
  EXPECT_LT(suction, suction_at_fault);
  EXPECT_LT(suction, healthy_suction);
  EXPECT_LT(got.downforce_n, want.downforce_n);
}

TEST(ThermoNodeFaults, AFaultNamingAnEngineTheRobotLacksIsAConfigError) {
  const auto& r = cromsci();
  const int too_many = static_cast<int>(r.params.engines.size()) + 1;
  try {
    plantFaultsFromScenario({valveStuck(1.0, 2, 0.5), engineFailure(2.0, too_many)}, "s.yaml", r.params);
    FAIL() << "accepted engine " << too_many;
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("s.yaml: faults[1].engine = " + std::to_string(too_many)),
              std::string::npos)
        << error.what();
  }
  // The model's own check, for params made by hand.
  ThermoParams params = r.params;
  params.faults.push_back(PlantFault{PlantFault::Kind::kEngineFailure, 0, 0, 0.0, too_many});
  try {
    ThermoModel model(params);
    FAIL() << "the model accepted engine " << too_many;
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("thermo: faults[0].engine = " + std::to_string(too_many)),
              std::string::npos)
        << error.what();
  }
}

TEST(ThermoNode, InputsListParses) {
  const auto all = parseThermoNodeInputs("leakage,valves,engines");
  EXPECT_TRUE(all.leakage && all.valves && all.engines);
  const auto some = parseThermoNodeInputs("leakage");
  EXPECT_TRUE(some.leakage && !some.valves && !some.engines);
  const auto none = parseThermoNodeInputs("none");
  EXPECT_FALSE(none.leakage || none.valves || none.engines);
  EXPECT_ANY_THROW(parseThermoNodeInputs("leakage,pressure"));
}

}  // namespace
}  // namespace climbsim::thermo
