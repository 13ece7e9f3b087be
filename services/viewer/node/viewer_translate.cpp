#include "viewer_translate.hpp"

#include <algorithm>

namespace climbsim::viewer {

ForceValue forceFromIdl(const climbsim::AdhesionForce& sample) {
  return {sample.step(), sample.t_ns(), sample.downforce_n(), sample.pf_x_m(), sample.pf_y_m(),
          sample.downforce_setpoint_n()};
}

ChamberValue chambersFromIdl(const climbsim::ChamberState& sample) {
  ChamberValue value;
  value.step = sample.step();
  value.t_ns = sample.t_ns();
  value.pressure_pa.assign(sample.pressure_pa().begin(), sample.pressure_pa().end());
  value.valve_opening.assign(sample.valve_opening().begin(), sample.valve_opening().end());
  return value;
}

PoseValue poseFromIdl(const climbsim::RobotState& sample) {
  PoseValue value;
  value.step = sample.step();
  value.t_ns = sample.t_ns();
  std::copy(sample.position_m().begin(), sample.position_m().end(), value.position_m.begin());
  std::copy(sample.orientation_wxyz().begin(), sample.orientation_wxyz().end(), value.orientation_wxyz.begin());
  value.fell = sample.fell();
  return value;
}

WheelsValue wheelsFromIdl(const climbsim::DriveState& sample) {
  WheelsValue value;
  value.step = sample.step();
  value.t_ns = sample.t_ns();
  for (const auto& wheel : sample.wheels()) {
    value.normal_n.push_back(wheel.normal_force_n());
    value.slip_mps.push_back(wheel.slip_mps());
    value.steering_rad.push_back(wheel.steering_rad());
  }
  return value;
}

LeakValue leakFromIdl(const climbsim::Leakage& sample) {
  LeakValue value;
  value.step = sample.step();
  value.t_ns = sample.t_ns();
  for (const auto& segment : sample.segments()) {
    value.segments[segment.segment().to_string()] = {segment.leak_area_m2(), segment.mean_gap_m()};
  }
  return value;
}

namespace {
bool ended(RunPhase phase) {
  return phase == RunPhase::kCompleted || phase == RunPhase::kStopped || phase == RunPhase::kFailed;
}
}  // namespace

void applySimTime(RunInfo& run, const climbsim::SimTime& sample) {
  if (ended(run.phase)) return;
  run.step = sample.step();
  run.t_ns = sample.t_ns();
  run.rtf_target = sample.realtime_factor();
  run.phase = sample.paused() ? RunPhase::kPaused : RunPhase::kRunning;
}

void applyRunStart(RunInfo& run, const climbsim::RunStart& sample) {
  run.dt_ns = sample.dt_ns();
  run.end_step = sample.end_step();
  run.roster.clear();
  for (const auto& entry : sample.roster()) {
    run.roster.push_back({entry.participant().to_string(), "", entry.period_steps(), entry.offset_steps()});
  }
  if (run.phase == RunPhase::kStarting) run.phase = RunPhase::kRunning;
}

void applyStop(RunInfo& run, const climbsim::Stop& sample) {
  switch (sample.kind()) {
    case climbsim::STOP_COMPLETED: run.phase = RunPhase::kCompleted; break;
    case climbsim::STOP_REQUESTED: run.phase = RunPhase::kStopped; break;
    default: run.phase = RunPhase::kFailed; break;
  }
  run.reason = sample.reason().to_string();
  if (!sample.culprit().to_string().empty()) run.reason = sample.culprit().to_string() + ": " + run.reason;
  // SimTime is best effort: the last one may have been lost; Stop is exact.
  run.step = sample.last_step() + 1;
  run.t_ns = std::max(run.t_ns, sample.t_ns());
}

void applyReady(RunInfo& run, const climbsim::ParticipantReady& sample) {
  run.hosts[sample.participant().to_string()] = sample.host().to_string();
}

climbsim::ClockControl controlToIdl(const ClockRequest& request, const std::string& sender) {
  climbsim::ClockControl control;
  switch (request.kind) {
    case ClockRequest::Kind::kPause: control.command(climbsim::CLOCK_PAUSE); break;
    case ClockRequest::Kind::kResume: control.command(climbsim::CLOCK_RESUME); break;
    case ClockRequest::Kind::kStep: control.command(climbsim::CLOCK_SINGLE_STEP); break;
    case ClockRequest::Kind::kStop: control.command(climbsim::CLOCK_STOP); break;
    case ClockRequest::Kind::kRealtimeFactor: control.command(climbsim::CLOCK_SET_REALTIME_FACTOR); break;
  }
  control.steps(request.steps);
  control.realtime_factor(request.realtime_factor);
  control.sender(sender);
  return control;
}

std::optional<HeightGrid> gridFromIdl(const climbsim::DepthGrid& sample) {
  const std::size_t n = static_cast<std::size_t>(sample.size()) * sample.size();
  if (sample.size() == 0 || sample.height_m().size() != n) return std::nullopt;
  return HeightGrid{static_cast<int>(sample.size()), sample.cell_m(), sample.height_m()};
}

std::set<std::string> recordedTopics(const climbsim::RunStart& run) {
  std::set<std::string> topics;
  for (const auto& entry : run.roster()) {
    for (const auto& t : entry.recorded_topics()) topics.insert(t.c_str());
  }
  return topics;
}

std::map<std::string, const climbsim::RecordedSample*> latestPerTopic(const climbsim::RecordBatch& batch) {
  std::map<std::string, const climbsim::RecordedSample*> latest;
  for (const auto& sample : batch.samples()) latest[sample.topic().c_str()] = &sample;
  return latest;
}

std::string joinedTopics(const std::set<std::string>& topics) {
  std::string text;
  for (const auto& t : topics) text += (text.empty() ? "" : ", ") + t;
  return text;
}

}  // namespace climbsim::viewer
