#include "clock_core.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"

namespace climbsim::clock {

namespace {
std::string seconds(std::chrono::milliseconds ms) {
  std::ostringstream out;
  out << static_cast<double>(ms.count()) / 1000.0 << " s";
  return out.str();
}

/// How long poll() may sleep when only an event can move the clock on.
constexpr auto kIdlePoll = std::chrono::milliseconds(500);
}  // namespace

void ClockParams::validate() const {
  if (roster.empty()) {
    throw ConfigError("--roster: empty; name at least one participant");
  }
  std::set<std::string> seen;
  for (const auto& name : roster) {
    validateName("--roster", name);
    if (!seen.insert(name).second) {
      throw ConfigError("--roster: participant '" + name + "' is named twice");
    }
  }
  if (dt_ns <= 0) {
    throw ConfigError("step length dt_ns = " + std::to_string(dt_ns) + "; it must be > 0");
  }
  if (end_step == 0) {
    throw ConfigError("end step = 0; a run needs at least one step");
  }
  if (!std::isfinite(realtime_factor) || realtime_factor < 0.0) {
    throw ConfigError("real-time factor = " + std::to_string(realtime_factor) + "; it must be >= 0");
  }
  if (start_timeout.count() <= 0) {
    throw ConfigError("start timeout = " + seconds(start_timeout) + "; it must be > 0");
  }
  if (step_timeout.count() <= 0) {
    throw ConfigError("step timeout = " + seconds(step_timeout) + "; it must be > 0");
  }
}

ClockCore::ClockCore(ClockParams params, ClockTransport& transport)
    : params_(std::move(params)), transport_(transport) {
  params_.validate();
  realtime_factor_ = params_.realtime_factor;
  paused_ = params_.start_paused;
}

void ClockCore::start(Time now) { start_deadline_ = now + params_.start_timeout; }

bool ClockCore::onRoster(const std::string& name) const {
  return std::find(params_.roster.begin(), params_.roster.end(), name) != params_.roster.end();
}

std::vector<std::string> ClockCore::missingReady() const {
  std::vector<std::string> missing;
  for (const auto& name : params_.roster) {
    if (ready_.count(name) == 0) {
      missing.push_back(name);
    }
  }
  std::sort(missing.begin(), missing.end());
  return missing;
}

std::vector<std::string> ClockCore::dueAt(std::uint64_t step) const {
  std::vector<std::string> due;
  for (const auto& [name, ready] : ready_) {  // std::map: sorted by name
    if (ready.entry.schedule.isDue(step)) {
      due.push_back(name);
    }
  }
  return due;
}

std::uint64_t ClockCore::lastGrantedStep() const { return granted_step_.value_or(0); }

void ClockCore::finish(StopKind kind, int exit_code, const std::string& culprit, const std::string& reason) {
  if (finished()) {
    return;  // the first end wins; Stop is idempotent
  }
  StopMsg stop;
  stop.run_id = params_.run_id;
  stop.last_step = lastGrantedStep();
  stop.t_ns = static_cast<std::int64_t>(next_step_) * params_.dt_ns;
  stop.kind = kind;
  stop.culprit = culprit;
  stop.reason = reason;
  stop_ = stop;
  exit_code_ = exit_code;
  phase_ = ClockPhase::kFinished;
  pending_.clear();
  transport_.publishStop(stop);
}

void ClockCore::fail(int exit_code, const std::string& culprit, const std::string& reason) {
  finish(StopKind::kFailed, exit_code, culprit, reason);
}

void ClockCore::onReady(const ReadyMsg& msg, Time /*now*/) {
  if (finished()) {
    return;
  }
  const std::string& name = msg.entry.participant;
  if (!onRoster(name)) {
    fail(kExitConfig, name,
         "participant '" + name + "' (" + msg.host + ":" + std::to_string(msg.pid) +
             ") is not on the roster (" + joinNames(params_.roster) + ")");
    return;
  }
  auto known = ready_.find(name);
  if (known != ready_.end()) {
    if (known->second.host == msg.host && known->second.pid == msg.pid) {
      return;  // the same announcement again
    }
    fail(kExitConfig, name,
         "two processes announce the participant name '" + name + "': " + known->second.host + ":" +
             std::to_string(known->second.pid) + " and " + msg.host + ":" + std::to_string(msg.pid));
    return;
  }
  try {
    msg.entry.schedule.validate("participant '" + name + "'");
  } catch (const ConfigError& e) {
    fail(kExitConfig, name, e.what());
    return;
  }
  for (const auto& [file, hash] : msg.idl_hashes) {
    auto first = idl_first_.emplace(file, std::make_pair(name, hash));
    if (!first.second && first.first->second.second != hash) {
      fail(kExitConfig, name,
           "participant '" + name + "' was built from another " + file + " than '" + first.first->second.first +
               "' (sha256 " + hash.substr(0, 12) + " vs " + first.first->second.second.substr(0, 12) + ")");
      return;
    }
  }
  if (phase_ != ClockPhase::kWaitingForReady) {
    fail(kExitFailed, name, "participant '" + name + "' announced ready after the run started");
    return;
  }
  ready_.emplace(name, msg);
}

void ClockCore::onDone(const DoneMsg& msg, Time /*now*/) {
  if (finished() || msg.run_id != params_.run_id || !onRoster(msg.participant)) {
    return;
  }
  switch (msg.kind) {
    case DoneKind::kFailed:
      fail(kExitFailed, msg.participant,
           "participant '" + msg.participant + "' failed" +
               (phase_ == ClockPhase::kRunning ? " at step " + std::to_string(msg.step) : std::string()) + ": " +
               msg.message);
      return;
    case DoneKind::kArmed:
      if (phase_ == ClockPhase::kArming) {
        armed_.insert(msg.participant);
      }
      return;
    case DoneKind::kStepDone:
      if (phase_ == ClockPhase::kRunning && granted_step_ && msg.step == *granted_step_) {
        pending_.erase(msg.participant);
      }
      return;
  }
}

void ClockCore::reanchor(Time now) { anchor_ = PacingAnchor{now, next_step_}; }

void ClockCore::publishSimTime(bool paused) {
  SimTimeMsg msg;
  msg.step = next_step_;
  msg.t_ns = static_cast<std::int64_t>(next_step_) * params_.dt_ns;
  msg.realtime_factor = realtime_factor_;
  msg.paused = paused;
  transport_.publishSimTime(msg);
}

void ClockCore::onControl(const ControlMsg& msg, Time now) {
  if (finished()) {
    return;
  }
  switch (msg.command) {
    case ControlCommand::kPause:
      if (!paused_) {
        paused_ = true;
        single_steps_left_ = 0;
      }
      return;
    case ControlCommand::kResume:
      if (paused_) {
        paused_ = false;
        single_steps_left_ = 0;
        reanchor(now);
      }
      return;
    case ControlCommand::kSingleStep:
      if (paused_) {
        single_steps_left_ += std::max<std::uint32_t>(msg.steps, 1);
        reanchor(now);
      }
      return;
    case ControlCommand::kStop:
      stop_requested_ = true;
      stop_requested_by_ = msg.sender;
      return;
    case ControlCommand::kSetRealtimeFactor:
      if (std::isfinite(msg.realtime_factor) && msg.realtime_factor >= 0.0) {
        realtime_factor_ = msg.realtime_factor;
        reanchor(now);
      }
      return;
  }
}

void ClockCore::onParticipantLost(const std::string& participant, const std::string& how, Time /*now*/) {
  if (finished() || ready_.count(participant) == 0) {
    return;
  }
  fail(kExitFailed, participant,
       "participant '" + participant + "' vanished (" + how + ")" +
           (granted_step_ ? " during step " + std::to_string(*granted_step_) : std::string(" before step 0")));
}

void ClockCore::startRun() {
  // Every input needs a producer on the roster, or its consumer would wait forever.
  std::set<std::string> produced;
  for (const auto& [name, ready] : ready_) {
    produced.insert(ready.entry.output_topics.begin(), ready.entry.output_topics.end());
  }
  for (const auto& [name, ready] : ready_) {
    for (const auto& topic : ready.entry.input_topics) {
      if (produced.count(topic) == 0) {
        fail(kExitConfig, name,
             "participant '" + name + "' reads topic '" + topic + "' that no participant on the roster writes");
        return;
      }
    }
  }
  RunStartMsg msg;
  msg.run_id = params_.run_id;
  msg.dt_ns = params_.dt_ns;
  msg.end_step = params_.end_step;
  for (const auto& [name, ready] : ready_) {
    msg.roster.push_back(ready.entry);
  }
  phase_ = ClockPhase::kArming;
  transport_.publishRunStart(msg);
}

ClockCore::Time ClockCore::poll(Time now) {
  if (stop_requested_ && phase_ != ClockPhase::kRunning && !finished()) {
    finish(StopKind::kRequested, kExitStopped, "",
           "stopped on request" + (stop_requested_by_.empty() ? std::string() : " of " + stop_requested_by_) +
               " before the run started");
    return now;
  }
  if (phase_ == ClockPhase::kWaitingForReady) {
    if (ready_.size() == params_.roster.size()) {
      startRun();
    } else if (now >= start_deadline_) {
      const auto missing = missingReady();
      fail(kExitStartTimeout, missing.front(),
           "start timeout after " + seconds(params_.start_timeout) + ": missing participant" +
               (missing.size() > 1 ? "s " : " ") + joinNames(missing) + " (never announced ready)");
      return now;
    } else {
      return std::min(start_deadline_, now + kIdlePoll);
    }
  }
  if (phase_ == ClockPhase::kArming) {
    const bool all_armed = armed_.size() == params_.roster.size();
    if (all_armed && transport_.grantReaders() >= static_cast<int>(params_.roster.size())) {
      phase_ = ClockPhase::kRunning;
      reanchor(now);
    } else if (now >= start_deadline_) {
      std::vector<std::string> unarmed;
      for (const auto& name : params_.roster) {
        if (armed_.count(name) == 0) {
          unarmed.push_back(name);
        }
      }
      std::sort(unarmed.begin(), unarmed.end());
      const std::string who = unarmed.empty() ? std::string("the clock's grant writer") : joinNames(unarmed);
      fail(kExitStartTimeout, unarmed.empty() ? std::string() : unarmed.front(),
           "start timeout after " + seconds(params_.start_timeout) + ": " + who +
               " did not match its data topics (are their producers and consumers running?)");
      return now;
    } else {
      return std::min(start_deadline_, now + std::chrono::milliseconds(10));
    }
  }
  while (phase_ == ClockPhase::kRunning) {
    if (!pending_.empty()) {
      const auto deadline = granted_at_ + params_.step_timeout;
      if (now >= deadline) {
        const std::vector<std::string> late(pending_.begin(), pending_.end());
        fail(kExitFailed, late.front(),
             "watchdog: participant" + std::string(late.size() > 1 ? "s " : " ") + joinNames(late) +
                 " did not finish step " + std::to_string(*granted_step_) + " within " + seconds(params_.step_timeout));
        return now;
      }
      return deadline;
    }
    if (stop_requested_) {
      finish(StopKind::kRequested, kExitStopped, "",
             "stopped on request" + (stop_requested_by_.empty() ? std::string() : " of " + stop_requested_by_) +
                 " before step " + std::to_string(next_step_));
      return now;
    }
    const auto release = pacedStart(anchor_, next_step_, params_.dt_ns, realtime_factor_);
    if (next_step_ >= params_.end_step) {
      if (now < release) {
        return release;  // the last step lasts its dt on the wall clock too
      }
      finish(StopKind::kCompleted, kExitOk, "", "end of run after " + std::to_string(params_.end_step) + " steps");
      return now;
    }
    if (paused_ && single_steps_left_ == 0) {
      // Observers (also late joiners of this best-effort topic) learn where the clock holds.
      if (now >= next_pause_announce_) {
        publishSimTime(true);
        next_pause_announce_ = now + kIdlePoll;
      }
      return next_pause_announce_;
    }
    if (now < release) {
      return release;
    }
    const auto due = dueAt(next_step_);
    publishSimTime(false);
    if (!due.empty()) {
      GrantMsg grant;
      grant.run_id = params_.run_id;
      grant.step = next_step_;
      grant.t_ns = static_cast<std::int64_t>(next_step_) * params_.dt_ns;
      grant.dt_ns = params_.dt_ns;
      pending_.insert(due.begin(), due.end());
      granted_step_ = next_step_;
      granted_at_ = now;
      transport_.publishGrant(grant);
    }
    ++next_step_;
    next_pause_announce_ = Time{};
    if (paused_ && single_steps_left_ > 0) {
      --single_steps_left_;
    }
  }
  return now;
}

}  // namespace climbsim::clock
