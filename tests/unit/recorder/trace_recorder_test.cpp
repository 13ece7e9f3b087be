// The recorder's rows without DDS: docs/scenario-files.md columns, zero-order hold, exact number
// formatting, bad samples dropped, summary.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/run_summary/run_summary.hpp"
#include "node/trace_recorder.hpp"

namespace climbsim::recorder {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line.substr(0, line.find('\n')));
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

TEST(TraceRecorder, ColumnsAreThoseOfTheDesign) {
  const auto c = traceColumns({"outer1", "radial1_2"}, 3);
  const std::vector<std::string> expected = {
      "t_s", "downforce_n", "pf_x_m", "pf_y_m", "p1_pa", "p2_pa", "p3_pa", "p4_pa", "p5_pa", "p6_pa", "p7_pa", "pr_pa",
      "valve1", "valve2", "valve3", "valve4", "valve5", "valve6", "valve7", "leak_area_m2_outer1",
      "leak_area_m2_radial1_2", "x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad", "wheel1_normal_n",
      "wheel2_normal_n", "wheel3_normal_n", "wheel1_slip_mps", "wheel2_slip_mps", "wheel3_slip_mps",
      "downforce_setpoint_n"};
  EXPECT_EQ(c, expected);
}

TEST(TraceRecorder, ColumnsFollowTheRobotsChambersReservoirAndWheels) {
  // A single chamber without a reservoir: one pressure, no reservoir, no valves; two wheels.
  const auto single = traceColumns({"outer1"}, 2, 1, false);
  const std::vector<std::string> expected = {
      "t_s", "downforce_n", "pf_x_m", "pf_y_m", "p1_pa", "leak_area_m2_outer1", "x_m", "y_m", "z_m", "roll_rad",
      "pitch_rad", "yaw_rad", "wheel1_normal_n", "wheel2_normal_n", "wheel1_slip_mps", "wheel2_slip_mps",
      "downforce_setpoint_n"};
  EXPECT_EQ(single, expected);
  // Thirteen chambers on a reservoir: p1..p13, pr, valve1..valve13.
  const auto ring = traceColumns({"outer1"}, 4, 13, true);
  EXPECT_EQ(ring[4], "p1_pa");
  EXPECT_EQ(ring[16], "p13_pa");
  EXPECT_EQ(ring[17], "pr_pa");
  EXPECT_EQ(ring[18], "valve1");
  EXPECT_EQ(ring[30], "valve13");
  // A ChamberState sized for another robot is dropped, not read past its end.
  TraceRecorder recorder({"outer1"}, {0.0}, 2, 1, false);
  climbsim::ChamberState seven;
  seven.source("thermo");
  seven.pressure_pa().assign(8, 90000.0);
  seven.valve_opening().assign(7, 0.5);
  recorder.update({seven}, {}, {}, {}, {});
  EXPECT_EQ(recorder.droppedSamples(), 1u);
  climbsim::ChamberState one;
  one.source("thermo");
  one.pressure_pa().assign(1, 95000.0);
  recorder.update({one}, {}, {}, {}, {});
  EXPECT_EQ(recorder.droppedSamples(), 1u);
  EXPECT_EQ(split(recorder.row(0))[4], "95000");
}

TEST(TraceRecorder, RollPitchYawInvertsTheZYXConstruction) {
  const double roll = 0.1, pitch = -0.4, yaw = 2.5;
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  const auto rpy = rollPitchYaw({q.w(), q.x(), q.y(), q.z()});
  EXPECT_NEAR(rpy[0], roll, 1e-12);
  EXPECT_NEAR(rpy[1], pitch, 1e-12);
  EXPECT_NEAR(rpy[2], yaw, 1e-12);
}

TEST(TraceRecorder, HoldsValuesRoundTripsExactlyAndDropsBadSamples) {
  TraceRecorder r({"outer1"}, {3.6e-5}, 1);
  const auto columns = r.columns();
  // Before any sample: the basic leak area, NaN elsewhere.
  auto cells = split(r.row(0));
  ASSERT_EQ(cells.size(), columns.size());
  EXPECT_EQ(std::stod(cells[19]), 3.6e-5);
  EXPECT_TRUE(std::isnan(std::stod(cells[1])));

  climbsim::AdhesionForce f;
  f.source("thermo");
  f.downforce_n(2200.0 + 1.0 / 3.0);
  climbsim::RobotState p;
  p.source("drive");
  p.position_m({1.0, 1.2, 0.0});
  p.orientation_wxyz({1.0, 0.0, 0.0, 0.0});
  climbsim::DriveState d;
  d.source("drive");
  climbsim::WheelState w;
  w.normal_force_n(700.0);
  d.wheels().push_back(w);
  r.update({}, {f}, {}, {p}, {d});
  cells = split(r.row(5'000'000));
  EXPECT_EQ(cells[0], "0.005000000");
  EXPECT_EQ(std::stod(cells[1]), 2200.0 + 1.0 / 3.0);  // %.17g: the double comes back bit for bit
  EXPECT_EQ(std::stod(cells[20]), 1.0);
  EXPECT_EQ(std::stod(cells[26]), 700.0);

  // A NaN force and a drive state with the wrong wheel count are dropped; the last valid holds.
  f.downforce_n(std::numeric_limits<double>::quiet_NaN());
  d.wheels().push_back(w);
  r.update({}, {f}, {}, {}, {d});
  cells = split(r.row(10'000'000));
  EXPECT_EQ(std::stod(cells[1]), 2200.0 + 1.0 / 3.0);
  EXPECT_EQ(r.droppedSamples(), 2u);

  const auto s = r.summary();
  EXPECT_EQ(s["steps"], 3);
  EXPECT_DOUBLE_EQ(s["sim_s"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(s["min_downforce_n"].get<double>(), 2200.0 + 1.0 / 3.0);
  EXPECT_FALSE(s["fell"].get<bool>());
  EXPECT_TRUE(s["fell_at_s"].is_null());

  // The first row that holds the fall gives its time; later rows do not move it.
  p.fell(true);
  r.update({}, {}, {}, {p}, {});
  r.row(15'000'000);
  r.row(20'000'000);
  EXPECT_TRUE(r.summary()["fell"].get<bool>());
  EXPECT_DOUBLE_EQ(r.summary()["fell_at_s"].get<double>(), 0.015);
}


// Slide: the robot slides only when every wheel in contact slips, faster than creep; the
// distance is the slide speed integrated over the rows, a failure beyond the scenario's limit.
TEST(TraceRecorder, SlideIsTheSmallestWheelSlipIntegratedAboveCreepAndFailsBeyondTheLimit) {
  TraceRecorder r({"outer1"}, {3.6e-5}, 2);
  climbsim::RobotState p;
  p.source("drive");
  p.position_m({1.0, 1.2, 0.0});
  p.orientation_wxyz({1.0, 0.0, 0.0, 0.0});
  const auto drive = [](double slip1, double slip2, double normal2 = 700.0) {
    climbsim::DriveState d;
    d.source("drive");
    climbsim::WheelState w1, w2;
    w1.normal_force_n(700.0);
    w1.slip_mps(slip1);
    w2.normal_force_n(normal2);
    w2.slip_mps(slip2);
    d.wheels() = {w1, w2};
    return d;
  };
  std::int64_t t = 0;
  r.update({}, {}, {}, {p}, {drive(0.0, 0.0)});
  r.row(t);
  // 1 s of rolling creep (1 mm/s on both wheels): no slide.
  for (int k = 0; k < 200; ++k) {
    r.update({}, {}, {}, {}, {drive(0.001, 0.001)});
    r.row(t += 5'000'000);
  }
  EXPECT_DOUBLE_EQ(r.summary()["slide_m"].get<double>(), 0.0);
  // One wheel scrubs at 0.2 m/s while the other grips: no slide of the robot either.
  for (int k = 0; k < 20; ++k) {
    r.update({}, {}, {}, {}, {drive(0.2, 0.0)});
    r.row(t += 5'000'000);
  }
  EXPECT_DOUBLE_EQ(r.summary()["slide_m"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(r.summary()["max_slip_mps"].get<double>(), 0.2);
  // Both slip, the slower at 0.1 m/s, for 40 ms: 4 mm, within the default 5 mm limit.
  for (int k = 0; k < 8; ++k) {
    r.update({}, {}, {}, {}, {drive(0.1, 0.3)});
    r.row(t += 5'000'000);
  }
  auto s = r.summary();
  EXPECT_NEAR(s["slide_m"].get<double>(), 0.004, 1e-12);
  EXPECT_DOUBLE_EQ(s["slide_limit_m"].get<double>(), kDefaultSlideLimitM);
  EXPECT_FALSE(s["slid"].get<bool>());
  EXPECT_FALSE(s["adhesion_failed"].get<bool>());
  // A wheel off the wall does not hold the robot: the slipping one decides. 2 mm more: 6 mm.
  for (int k = 0; k < 4; ++k) {
    r.update({}, {}, {}, {}, {drive(0.1, 0.0, 0.0)});
    r.row(t += 5'000'000);
  }
  s = r.summary();
  EXPECT_NEAR(s["slide_m"].get<double>(), 0.006, 1e-12);
  EXPECT_TRUE(s["slid"].get<bool>());
  EXPECT_TRUE(s["adhesion_failed"].get<bool>());
  EXPECT_FALSE(s["fell"].get<bool>());
  r.setSlideLimit(0.01);
  EXPECT_FALSE(r.summary()["slid"].get<bool>());
  EXPECT_THROW(r.setSlideLimit(0.0), ConfigError);
}

}  // namespace
}  // namespace climbsim::recorder

namespace climbsim::recorder {
namespace {

TEST(RunSummary, AFallOutcomeSaysFellEvenBeforeARowHoldsIt) {
  TraceRecorder recorder({"outer_1"}, {1e-5}, 3);
  recorder.row(0);
  const auto completed = run_summary::runSummary(recorder.summary(), "s", 2.0, {"completed", "end of run", "", 0});
  EXPECT_EQ(completed["fell"], false);
  EXPECT_EQ(completed["completed"], true);
  EXPECT_DOUBLE_EQ(completed["realtime_factor"].get<double>(), completed["sim_s"].get<double>() / 2.0);
  const auto fell = run_summary::runSummary(recorder.summary(), "s", 2.0, {"fell", "FELL at t = 2.1 s", "drive", 5});
  EXPECT_EQ(fell["fell"], true);
  EXPECT_EQ(fell["adhesion_failed"], true);
  EXPECT_EQ(fell["completed"], false);
  EXPECT_EQ(fell["exit_code"], 5);
  EXPECT_EQ(fell["culprit"], "drive");
  // No row held the fall (the run ended at the fall's step): the time comes from the reason.
  EXPECT_DOUBLE_EQ(fell["fell_at_s"].get<double>(), 2.1);
  EXPECT_TRUE(completed["fell_at_s"].is_null());
  EXPECT_EQ(run_summary::fellAtInReason("FELL at t = 2.105 s: the robot left the wall"), std::optional<double>(2.105));
  EXPECT_EQ(run_summary::fellAtInReason("participant 'drive' failed"), std::nullopt);
}

TEST(TraceRecorder, WithEndOnFallTheTraceEndsBeforeItsFirstRowThatHoldsTheFall) {
  for (const bool end_on_fall : {false, true}) {
    TraceRecorder recorder({"outer_1"}, {1e-5}, 3);
    recorder.setEndOnFall(end_on_fall);
    climbsim::RobotState pose;
    pose.orientation_wxyz({1.0, 0.0, 0.0, 0.0});
    recorder.update({}, {}, {}, {pose}, {});
    EXPECT_FALSE(recorder.row(0).empty());
    pose.fell(true);
    recorder.update({}, {}, {}, {pose}, {});
    // The fall's row and every later one: written only when the run goes on after a fall.
    EXPECT_EQ(recorder.row(5'000'000).empty(), end_on_fall);
    recorder.update({}, {}, {}, {pose}, {});
    EXPECT_EQ(recorder.row(10'000'000).empty(), end_on_fall);
    EXPECT_EQ(recorder.endedAtFall(), end_on_fall);
    const auto summary = run_summary::runSummary(recorder.summary(), "s", 1.0, {"fell", "", "drive", 5});
    EXPECT_DOUBLE_EQ(summary["fell_at_s"].get<double>(), 0.005) << "the time of the row that would hold it";
  }
}

TEST(RunSummary, ARowThatHoldsTheFallKeepsItsOwnTime) {
  TraceRecorder recorder({"outer_1"}, {1e-5}, 3);
  climbsim::RobotState pose;
  pose.orientation_wxyz({1.0, 0.0, 0.0, 0.0});
  pose.fell(true);
  recorder.update({}, {}, {}, {pose}, {});
  recorder.row(5'000'000);
  const auto fell = run_summary::runSummary(recorder.summary(), "s", 2.0, {"fell", "FELL at t = 9.999 s: ...", "drive", 5});
  EXPECT_DOUBLE_EQ(fell["fell_at_s"].get<double>(), 0.005);
}

}  // namespace
}  // namespace climbsim::recorder

namespace climbsim::recorder {
namespace {

climbsim::AdhesionForce force(double f_n, double pf_x_m, double pf_y_m) {
  climbsim::AdhesionForce f;
  f.source("thermo");
  f.downforce_n(f_n);
  f.pf_x_m(pf_x_m);
  f.pf_y_m(pf_y_m);
  return f;
}

TEST(TraceRecorder, ThePublishedSetPointAndASealOverNothingReachTheTraceAndTheSummary) {
  TraceRecorder r({"outer1", "outer2"}, {3.6e-5, 3.6e-5}, 1);
  auto f = force(0.0, 0.0, 0.0);
  r.update({}, {f}, {}, {}, {});
  EXPECT_EQ(split(r.row(0)).back(), "0") << "no set-point stated";
  EXPECT_TRUE(r.summary()["downforce_setpoint_n"].is_null());
  EXPECT_TRUE(r.summary()["seal_over_nothing"].is_null());
  f.downforce_setpoint_n(1800.0);
  climbsim::Leakage part;
  part.source("sealing");
  climbsim::LeakageSegment over;
  over.segment("outer2");
  over.leak_area_m2(7e-3);
  over.no_surface_share(0.45);
  climbsim::LeakageSegment on;
  on.segment("outer1");
  on.leak_area_m2(3.6e-5);
  on.no_surface_share(0.05);  // a few pixels over a deep pore: below the threshold
  part.segments({on, over});
  r.update({}, {f}, {part}, {}, {});
  EXPECT_EQ(split(r.row(5'000'000)).back(), "1800");
  f.downforce_setpoint_n(std::numeric_limits<double>::infinity());
  r.update({}, {f}, {part}, {}, {});  // dropped: the last valid set-point holds
  r.row(10'000'000);
  const auto s = r.summary();
  EXPECT_EQ(s["downforce_setpoint_n"].get<double>(), 1800.0);
  ASSERT_TRUE(s["seal_over_nothing"].is_object()) << s.dump();
  EXPECT_DOUBLE_EQ(s["seal_over_nothing"]["first_at_s"].get<double>(), 0.005);
  EXPECT_EQ(s["seal_over_nothing"]["segments"], nlohmann::json::array({"outer2"}));
  EXPECT_DOUBLE_EQ(s["seal_over_nothing"]["max_share"].get<double>(), 0.45);
  EXPECT_EQ(s["dropped_samples"], 1);
}

TEST(TraceRecorder, DownforceStatisticsCountOnlyTheRowsFromTheEndOfTheHold) {
  // The vacuum builds from ambient (F = 0 in row 0) while the robot is held; the minimum,
  // the mean and the largest P_F shift are those of the rows from the release on.
  TraceRecorder r({"outer1"}, {3.6e-5}, 1);
  r.setDownforceFrom(10'000'000);  // released at 10 ms
  const std::vector<climbsim::AdhesionForce> forces = {force(0.0, 0.3, 0.0), force(500.0, 0.2, 0.0),
                                                       force(2000.0, 0.03, 0.04), force(1500.0, 0.0, 0.01),
                                                       force(2500.0, 0.0, 0.0)};
  for (std::size_t k = 0; k < forces.size(); ++k) {
    r.update({}, {forces[k]}, {}, {}, {});
    r.row(static_cast<std::int64_t>(k) * 5'000'000);
  }
  const auto s = r.summary();
  EXPECT_DOUBLE_EQ(s["downforce_from_s"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(s["min_downforce_n"].get<double>(), 1500.0);
  EXPECT_DOUBLE_EQ(s["mean_downforce_n"].get<double>(), 2000.0);
  EXPECT_DOUBLE_EQ(s["max_pf_shift_m"].get<double>(), 0.05);

  // Without a hold every row counts: the evacuation from ambient is part of the run.
  TraceRecorder unheld({"outer1"}, {3.6e-5}, 1);
  unheld.update({}, {forces[0]}, {}, {}, {});
  unheld.row(0);
  EXPECT_DOUBLE_EQ(unheld.summary()["min_downforce_n"].get<double>(), 0.0);
  EXPECT_THROW(unheld.setDownforceFrom(-1), ConfigError);

  // A run that ends before the release has no such rows.
  TraceRecorder short_run({"outer1"}, {3.6e-5}, 1);
  short_run.setDownforceFrom(1'000'000'000);
  short_run.update({}, {forces[2]}, {}, {}, {});
  short_run.row(0);
  EXPECT_TRUE(short_run.summary()["min_downforce_n"].is_null());
  EXPECT_TRUE(short_run.summary()["mean_downforce_n"].is_null());
}

}  // namespace
}  // namespace climbsim::recorder
