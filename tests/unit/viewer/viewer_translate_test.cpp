// IDL samples -> the viewer's model, and the page's requests -> ClockControl.
#include <gtest/gtest.h>

#include "viewer_translate.hpp"

namespace climbsim::viewer {
namespace {

TEST(ViewerTranslate, ForceAndChambers) {
  climbsim::AdhesionForce force;
  force.step(9);
  force.t_ns(45'000'000);
  force.downforce_n(2200.5);
  force.pf_x_m(0.01);
  force.pf_y_m(-0.02);
  const ForceValue f = forceFromIdl(force);
  EXPECT_EQ(f.step, 9u);
  EXPECT_EQ(f.downforce_n, 2200.5);
  EXPECT_EQ(f.pf_y_m, -0.02);

  climbsim::ChamberState chambers;
  chambers.step(3);
  for (int i = 0; i < 8; ++i) chambers.pressure_pa().push_back(90000.0 + i);
  for (int i = 0; i < 7; ++i) chambers.valve_opening().push_back(0.1 * i);
  const ChamberValue c = chambersFromIdl(chambers);
  EXPECT_EQ(c.pressure_pa[7], 90007.0);
  EXPECT_EQ(c.valve_opening[6], 0.1 * 6);
}

TEST(ViewerTranslate, WheelsAndLeakage) {
  climbsim::DriveState drive;
  climbsim::WheelState wheel;
  wheel.normal_force_n(210.0);
  wheel.slip_mps(0.001);
  drive.wheels().push_back(wheel);
  drive.wheels().push_back(wheel);
  const WheelsValue w = wheelsFromIdl(drive);
  ASSERT_EQ(w.normal_n.size(), 2u);
  EXPECT_EQ(w.slip_mps[1], 0.001);

  climbsim::Leakage leakage;
  climbsim::LeakageSegment segment;
  segment.segment("radial6_1");
  segment.leak_area_m2(1e-5);
  segment.mean_gap_m(2e-4);
  leakage.segments().push_back(segment);
  const LeakValue l = leakFromIdl(leakage);
  EXPECT_EQ(l.segments.at("radial6_1").first, 1e-5);
}

TEST(ViewerTranslate, RunPhasesFollowTheClock) {
  RunInfo run;
  climbsim::RunStart start;
  start.dt_ns(5'000'000);
  start.end_step(4000);
  climbsim::RosterEntry entry;
  entry.participant("thermo");
  entry.period_steps(1);
  start.roster().push_back(entry);
  applyRunStart(run, start);
  EXPECT_EQ(run.phase, RunPhase::kRunning);
  ASSERT_EQ(run.roster.size(), 1u);

  climbsim::ParticipantReady ready;
  ready.participant("thermo");
  ready.host("lab2");
  applyReady(run, ready);
  EXPECT_EQ(run.hosts.at("thermo"), "lab2");

  climbsim::SimTime time;
  time.step(10);
  time.t_ns(50'000'000);
  time.paused(true);
  time.realtime_factor(1.0);
  applySimTime(run, time);
  EXPECT_EQ(run.phase, RunPhase::kPaused);
  EXPECT_EQ(run.t_ns, 50'000'000);

  climbsim::Stop stop;
  stop.kind(climbsim::STOP_FAILED);
  stop.culprit("drive");
  stop.reason("vanished");
  stop.last_step(11);
  applyStop(run, stop);
  EXPECT_EQ(run.phase, RunPhase::kFailed);
  EXPECT_EQ(run.reason, "drive: vanished");
  time.paused(false);
  applySimTime(run, time);  // a late SimTime does not revive an ended run
  EXPECT_EQ(run.phase, RunPhase::kFailed);
}

TEST(ViewerTranslate, RecordBatchesGiveTheLatestSampleOfEachTopic) {
  climbsim::RunStart run;
  climbsim::RosterEntry recorder, thermo;
  recorder.participant("recorder");
  recorder.recorded_topics().push_back("thermo/ChamberState");
  recorder.recorded_topics().push_back("scene/DepthGrid");
  thermo.participant("thermo");
  run.roster().push_back(recorder);
  run.roster().push_back(thermo);
  EXPECT_EQ(recordedTopics(run), (std::set<std::string>{"scene/DepthGrid", "thermo/ChamberState"}));
  EXPECT_EQ(joinedTopics(recordedTopics(run)), "scene/DepthGrid, thermo/ChamberState");

  climbsim::RecordBatch batch;
  for (const auto& [topic, step] : std::vector<std::pair<std::string, int>>{
           {"thermo/ChamberState", 8}, {"thermo/AdhesionForce", 8}, {"thermo/ChamberState", 9}, {"thermo/AdhesionForce", 9},
           {"thermo/ChamberState", 10}}) {
    climbsim::RecordedSample sample;
    sample.topic(topic);
    sample.step(static_cast<std::uint64_t>(step));
    batch.samples().push_back(sample);
  }
  const auto latest = latestPerTopic(batch);
  ASSERT_EQ(latest.size(), 2u);
  EXPECT_EQ(latest.at("thermo/ChamberState")->step(), 10u);
  EXPECT_EQ(latest.at("thermo/AdhesionForce")->step(), 9u);
}

TEST(ViewerTranslate, DepthGridBecomesAHeightGridUnlessTorn) {
  climbsim::DepthGrid sample;
  sample.size(2);
  sample.cell_m(0.0125);
  sample.height_m({0.001f, -0.002f, 0.0f, 0.003f});
  const auto grid = gridFromIdl(sample);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->size, 2);
  EXPECT_EQ(grid->height_m[1], -0.002f);
  sample.height_m().pop_back();
  EXPECT_FALSE(gridFromIdl(sample));
}

TEST(ViewerTranslate, ClockRequestToControl) {
  ClockRequest request;
  request.kind = ClockRequest::Kind::kStep;
  request.steps = 3;
  const auto control = controlToIdl(request, "viewer");
  EXPECT_EQ(control.command(), climbsim::CLOCK_SINGLE_STEP);
  EXPECT_EQ(control.steps(), 3u);
  EXPECT_EQ(control.sender().to_string(), "viewer");
  request.kind = ClockRequest::Kind::kRealtimeFactor;
  request.realtime_factor = 2.0;
  EXPECT_EQ(controlToIdl(request, "viewer").command(), climbsim::CLOCK_SET_REALTIME_FACTOR);
}

}  // namespace
}  // namespace climbsim::viewer
