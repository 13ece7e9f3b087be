#include "clock_translate.hpp"

namespace climbsim::clock {

RosterEntry fromIdl(const climbsim::RosterEntry& idl) {
  RosterEntry msg;
  msg.participant = idl.participant().c_str();
  msg.schedule = Schedule{idl.period_steps(), idl.offset_steps()};
  for (const auto& t : idl.input_topics()) {
    msg.input_topics.emplace_back(t.c_str());
  }
  for (const auto& t : idl.output_topics()) {
    msg.output_topics.emplace_back(t.c_str());
  }
  for (const auto& t : idl.same_step_inputs()) {
    msg.same_step_inputs.emplace_back(t.c_str());
  }
  for (const auto& t : idl.recorded_topics()) {
    msg.recorded_topics.emplace_back(t.c_str());
  }
  for (const auto& t : idl.input_sources()) {
    msg.input_sources.emplace_back(t.c_str());
  }
  return msg;
}

ReadyMsg fromIdl(const climbsim::ParticipantReady& idl) {
  ReadyMsg msg;
  msg.entry = fromIdl(idl.entry());
  // The key names the participant; the entry must agree with it.
  msg.entry.participant = idl.participant().c_str();
  for (const auto& h : idl.idl_hashes()) {
    msg.idl_hashes.emplace_back(h.file().c_str(), h.sha256().c_str());
  }
  msg.host = idl.host().c_str();
  msg.pid = idl.pid();
  return msg;
}

DoneMsg fromIdl(const climbsim::StepDone& idl) {
  DoneMsg msg;
  msg.participant = idl.participant().c_str();
  msg.run_id = idl.run_id();
  msg.progress_step = idl.progress_step();
  switch (idl.kind()) {
    case climbsim::ARMED:
      msg.kind = DoneKind::kArmed;
      break;
    case climbsim::FAILED:
      msg.kind = DoneKind::kFailed;
      break;
    case climbsim::FELL:
      msg.kind = DoneKind::kFell;
      break;
    case climbsim::STEP_DONE:
    default:
      msg.kind = DoneKind::kStepDone;
      break;
  }
  msg.message = idl.message().c_str();
  return msg;
}

ControlMsg fromIdl(const climbsim::ClockControl& idl) {
  ControlMsg msg;
  switch (idl.command()) {
    case climbsim::CLOCK_PAUSE:
      msg.command = ControlCommand::kPause;
      break;
    case climbsim::CLOCK_RESUME:
      msg.command = ControlCommand::kResume;
      break;
    case climbsim::CLOCK_SINGLE_STEP:
      msg.command = ControlCommand::kSingleStep;
      break;
    case climbsim::CLOCK_STOP:
      msg.command = ControlCommand::kStop;
      break;
    case climbsim::CLOCK_SET_REALTIME_FACTOR:
    default:
      msg.command = ControlCommand::kSetRealtimeFactor;
      break;
  }
  msg.steps = idl.steps();
  msg.realtime_factor = idl.realtime_factor();
  msg.sender = idl.sender().c_str();
  return msg;
}

climbsim::RosterEntry toIdl(const RosterEntry& msg) {
  climbsim::RosterEntry idl;
  idl.participant(msg.participant);
  idl.period_steps(msg.schedule.period_steps);
  idl.offset_steps(msg.schedule.offset_steps);
  for (const auto& t : msg.input_topics) {
    idl.input_topics().push_back(t);
  }
  for (const auto& t : msg.output_topics) {
    idl.output_topics().push_back(t);
  }
  for (const auto& t : msg.same_step_inputs) {
    idl.same_step_inputs().push_back(t);
  }
  for (const auto& t : msg.recorded_topics) {
    idl.recorded_topics().push_back(t);
  }
  for (const auto& t : msg.input_sources) {
    idl.input_sources().push_back(t);
  }
  return idl;
}

climbsim::RunStart toIdl(const RunStartMsg& msg) {
  climbsim::RunStart idl;
  idl.run_id(msg.run_id);
  idl.dt_ns(msg.dt_ns);
  idl.end_step(msg.end_step);
  idl.window_steps(msg.window_steps);
  for (const auto& entry : msg.roster) {
    idl.roster().push_back(toIdl(entry));
  }
  return idl;
}

climbsim::StepGrant toIdl(const GrantMsg& msg) {
  climbsim::StepGrant idl;
  idl.run_id(msg.run_id);
  idl.horizon_step(msg.horizon_step);
  idl.t_ns(msg.t_ns);
  idl.dt_ns(msg.dt_ns);
  return idl;
}

climbsim::Stop toIdl(const StopMsg& msg) {
  climbsim::Stop idl;
  idl.run_id(msg.run_id);
  idl.last_step(msg.last_step);
  idl.t_ns(msg.t_ns);
  switch (msg.kind) {
    case StopKind::kCompleted:
      idl.kind(climbsim::STOP_COMPLETED);
      break;
    case StopKind::kRequested:
      idl.kind(climbsim::STOP_REQUESTED);
      break;
    case StopKind::kFailed:
      idl.kind(climbsim::STOP_FAILED);
      break;
    case StopKind::kFell:
      idl.kind(climbsim::STOP_FELL);
      break;
  }
  idl.culprit(msg.culprit.substr(0, 63));
  idl.reason(msg.reason.substr(0, 511));
  return idl;
}

climbsim::SimTime toIdl(const SimTimeMsg& msg) {
  climbsim::SimTime idl;
  idl.step(msg.step);
  idl.t_ns(msg.t_ns);
  idl.realtime_factor(msg.realtime_factor);
  idl.paused(msg.paused);
  return idl;
}

}  // namespace climbsim::clock
