#include "clock_core.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"
#include "climbsim/topic_names.hpp"

namespace climbsim::clock {

namespace {
std::string seconds(std::chrono::milliseconds ms) {
  std::ostringstream out;
  out << static_cast<double>(ms.count()) / 1000.0 << " s";
  return out.str();
}

/// How long poll() may sleep when only an event can move the clock on.
constexpr auto kIdlePoll = std::chrono::milliseconds(500);
/// Who the IDL hashes of ClockParams belong to in messages.
constexpr const char* kClockName = "clock";
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
  if (max_pause && max_pause->count() <= 0) {
    throw ConfigError("max pause = " + seconds(*max_pause) + "; it must be > 0");
  }
  if (window_steps < 1) {
    throw ConfigError("window_steps = 0; it must be >= 1 (1 = one grant per step)");
  }
  if (max_window_steps > 0 && window_steps > max_window_steps) {
    throw ConfigError("window_steps = " + std::to_string(window_steps) + "; the step-data queues hold at most " +
                      std::to_string(max_window_steps) + " (QoS history depth - 2)");
  }
}

ClockCore::ClockCore(ClockParams params, ClockTransport& transport)
    : params_(std::move(params)), transport_(transport) {
  params_.validate();
  realtime_factor_ = params_.realtime_factor;
  paused_ = params_.start_paused;
  for (const auto& [file, hash] : params_.idl_hashes) {
    idl_first_.emplace(file, std::make_pair(std::string(kClockName), hash));
  }
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

std::uint64_t ClockCore::reachedStep() const {
  if (progress_.empty()) {
    return 0;
  }
  std::uint64_t reached = std::numeric_limits<std::uint64_t>::max();
  for (const auto& [name, progress] : progress_) {
    reached = std::min(reached, progress);
  }
  return reached;
}

std::uint64_t ClockCore::progressOf(const std::string& participant) const {
  const auto it = progress_.find(participant);
  return it == progress_.end() ? 0 : it->second;
}

void ClockCore::finish(StopKind kind, int exit_code, const std::string& culprit, const std::string& reason) {
  if (finished()) {
    return;  // the first end wins; Stop is idempotent
  }
  StopMsg stop;
  stop.run_id = params_.run_id;
  stop.last_step = horizon_ > 0 ? horizon_ - 1 : 0;
  stop.t_ns = static_cast<std::int64_t>(horizon_) * params_.dt_ns;
  stop.kind = kind;
  stop.culprit = culprit;
  stop.reason = reason;
  stop_ = stop;
  exit_code_ = exit_code;
  phase_ = ClockPhase::kFinished;
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
      const std::string& other = first.first->second.first;
      fail(kExitConfig, name,
           "participant '" + name + "' was built from another " + file + " than " +
               (other == kClockName ? std::string("the clock") : "'" + other + "'") + " (sha256 " +
               hash.substr(0, 12) + " vs " + first.first->second.second.substr(0, 12) +
               "): it speaks another protocol; rebuild it from this checkout");
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
               (phase_ == ClockPhase::kRunning ? " at step " + std::to_string(msg.progress_step) : std::string()) +
               ": " + msg.message);
      return;
    case DoneKind::kFell:
      // Like a stop: the horizon freezes, everyone finishes the steps below it, then Stop.
      if (phase_ == ClockPhase::kRunning && !fell_) {
        fell_ = std::make_pair(msg.participant, msg.message);
        stop_requested_ = true;
      }
      return;
    case DoneKind::kArmed:
      if (phase_ == ClockPhase::kArming) {
        armed_.insert(msg.participant);
      }
      return;
    case DoneKind::kStepDone: {
      auto it = progress_.find(msg.participant);
      if (phase_ != ClockPhase::kRunning || it == progress_.end()) {
        return;
      }
      const std::uint64_t progress = std::min(msg.progress_step, params_.end_step);
      // Progress may pass the horizon only over steps at which the participant is not due.
      const auto& schedule = ready_.at(msg.participant).entry.schedule;
      if (progress > horizon_ && schedule.nextDueFrom(horizon_) < progress) {
        fail(kExitFailed, msg.participant,
             "participant '" + msg.participant + "' reported progress to step " + std::to_string(progress) +
                 " beyond the horizon " + std::to_string(horizon_) + " (protocol violation)");
        return;
      }
      it->second = std::max(it->second, progress);
      return;
    }
  }
}

void ClockCore::reanchor(Time now) { anchor_ = PacingAnchor{now, horizon_}; }

void ClockCore::publishSimTime(bool paused) {
  SimTimeMsg msg;
  msg.step = reached_;
  msg.t_ns = static_cast<std::int64_t>(reached_) * params_.dt_ns;
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
        paused_since_ = now;
        pause_limit_ = horizon_;  // freezes H: participants finish the steps below it
      }
      return;
    case ControlCommand::kResume:
      if (paused_) {
        paused_ = false;
        reanchor(now);
      }
      return;
    case ControlCommand::kSingleStep:
      if (paused_) {
        pause_limit_ = std::max(pause_limit_, horizon_) + std::max<std::uint32_t>(msg.steps, 1);
        paused_since_ = now;
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
           (phase_ == ClockPhase::kRunning && horizon_ > 0
                ? " at step " + std::to_string(progressOf(participant))
                : std::string(" before step 0")));
}

void ClockCore::onStartStalled(const std::string& participant, const std::string& reason) {
  if (finished() || phase_ == ClockPhase::kRunning || !onRoster(participant)) {
    return;
  }
  fail(kExitRetryStart, participant, reason);
}

std::optional<std::string> ClockCore::zeroLagCycle() const {
  // Edges producer -> consumer for every input read with lag 0; a cycle of them deadlocks.
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> edges;  // from -> {to, topic}
  for (const auto& [consumer, ready] : ready_) {
    for (const auto& topic : ready.entry.same_step_inputs) {
      for (const auto& [producer, p] : ready_) {
        const auto& outs = p.entry.output_topics;
        if (std::find(outs.begin(), outs.end(), topic) != outs.end()) {
          edges[producer].emplace_back(consumer, topic);
        }
      }
    }
  }
  std::map<std::string, int> state;  // 0 new, 1 on the path, 2 done
  std::vector<std::pair<std::string, std::string>> path;  // {participant, topic to the next}
  std::optional<std::string> cycle;
  std::function<void(const std::string&)> visit = [&](const std::string& node) {
    state[node] = 1;
    for (const auto& [next, topic] : edges[node]) {
      if (cycle) return;
      path.emplace_back(node, topic);
      if (state[next] == 1) {
        std::string text;
        bool on = false;
        for (const auto& [who, via] : path) {
          on = on || who == next;
          if (on) text += who + " -(" + via + ")-> ";
        }
        cycle = text + next;
      } else if (state[next] == 0) {
        visit(next);
      }
      path.pop_back();
    }
    state[node] = 2;
  };
  for (const auto& [name, ready] : ready_) {
    if (!cycle && state[name] == 0) visit(name);
  }
  return cycle;
}

void ClockCore::startRun() {
  // A command of the robot has one writer: two controllers would fight over the valves.
  for (const char* topic : topic::kSingleWriterTopics) {
    std::vector<std::string> writers;
    for (const auto& [name, ready] : ready_) {
      const auto& outs = ready.entry.output_topics;
      if (std::find(outs.begin(), outs.end(), topic) != outs.end()) writers.push_back(name);
    }
    if (writers.size() > 1) {
      fail(kExitConfig, writers[1],
           "participants '" + writers[0] + "' and '" + writers[1] + "' both write topic '" + topic +
               "': a command of the robot has one writer (a controller of your own beside the reference "
               "controller needs `controller: {type: external}` in the scenario, which leaves the valves to it)");
      return;
    }
  }
  // Every input needs a producer on the roster, or its consumer would wait forever.
  std::set<std::string> produced;
  for (const auto& [name, ready] : ready_) {
    produced.insert(ready.entry.output_topics.begin(), ready.entry.output_topics.end());
  }
  for (const auto& [name, ready] : ready_) {
    for (const auto* topics : {&ready.entry.input_topics, &ready.entry.recorded_topics}) {
      for (const auto& topic : *topics) {
        if (produced.count(topic) == 0) {
          fail(kExitConfig, name,
               "participant '" + name + "' reads topic '" + topic + "' that no participant on the roster writes");
          return;
        }
      }
    }
    for (const auto& topic : ready.entry.same_step_inputs) {
      const auto& ins = ready.entry.input_topics;
      if (std::find(ins.begin(), ins.end(), topic) == ins.end()) {
        fail(kExitConfig, name,
             "participant '" + name + "' reads topic '" + topic + "' with lag 0 but does not list it as an input");
        return;
      }
    }
  }
  if (const auto cycle = zeroLagCycle()) {
    fail(kExitConfig, "",
         "inputs read with lag 0 close a cycle, which would deadlock: " + *cycle +
             " (give one of these inputs a lag of one step)");
    return;
  }
  RunStartMsg msg;
  msg.run_id = params_.run_id;
  msg.dt_ns = params_.dt_ns;
  msg.end_step = params_.end_step;
  msg.window_steps = params_.window_steps;
  for (const auto& [name, ready] : ready_) {
    msg.roster.push_back(ready.entry);
    progress_[name] = std::min(ready.entry.schedule.nextDueFrom(0), params_.end_step);
  }
  phase_ = ClockPhase::kArming;
  transport_.publishRunStart(msg);
}

std::uint64_t ClockCore::horizonTarget(Time now) const {
  std::uint64_t target = std::min<std::uint64_t>(params_.end_step, reached_ + params_.window_steps);
  if (paused_) {
    target = std::min(target, pause_limit_);
  }
  if (realtime_factor_ > 0.0 && now >= anchor_.wall) {
    // Step k may start at pacedStart(anchor, k): the released steps end at `released`.
    const long double elapsed_ns = std::chrono::duration<long double, std::nano>(now - anchor_.wall).count();
    const auto steps = static_cast<std::uint64_t>(
        std::floor(elapsed_ns * realtime_factor_ / static_cast<long double>(params_.dt_ns)));
    std::uint64_t released = anchor_.step + steps + 1;
    // Round-off must never release a step before its time.
    while (released > anchor_.step && pacedStart(anchor_, released - 1, params_.dt_ns, realtime_factor_) > now) {
      --released;
    }
    target = std::min(target, released);
  }
  return std::max(target, horizon_);
}

void ClockCore::grant(std::uint64_t horizon, Time now) {
  if (reached_ >= horizon_) {
    reached_at_ = now;  // work is outstanding again: the watchdog counts from here
  }
  horizon_ = horizon;
  GrantMsg msg;
  msg.run_id = params_.run_id;
  msg.horizon_step = horizon_;
  msg.t_ns = static_cast<std::int64_t>(horizon_) * params_.dt_ns;
  msg.dt_ns = params_.dt_ns;
  transport_.publishGrant(msg);
  // Observers (SimTime) at most every kSimTimePeriod, and always the first horizon (it marks
  // the start) and the last one (where the run ends).
  const bool last = horizon_ >= params_.end_step;
  if (!last_sim_time_ || now - *last_sim_time_ >= kSimTimePeriod || last) {
    last_sim_time_ = now;
    publishSimTime(false);
  }
}

std::string ClockCore::watchdogCulprits(std::vector<std::string>& names) const {
  // The least progress is the root of a stall: everyone waiting on a participant has
  // reported more progress than the step it is stuck in. Recorders lag behind the
  // batches of others, so they are blamed only when nobody else has work left.
  names.clear();
  for (const bool recorders : {false, true}) {
    std::uint64_t least = std::numeric_limits<std::uint64_t>::max();
    for (const auto& [name, progress] : progress_) {
      const bool is_recorder = !ready_.at(name).entry.recorded_topics.empty();
      if (is_recorder != recorders || progress >= horizon_) continue;
      if (progress < least) {
        least = progress;
        names.clear();
      }
      if (progress == least) names.push_back(name);
    }
    if (!names.empty()) return std::to_string(least);
  }
  return std::to_string(reached_);
}

bool ClockCore::watchdogExpired(Time now) {
  if (reached_ >= horizon_ || now < reached_at_ + params_.step_timeout) {
    return false;
  }
  std::vector<std::string> late;
  const std::string step = watchdogCulprits(late);
  fail(kExitFailed, late.empty() ? std::string() : late.front(),
       "watchdog: participant" + std::string(late.size() > 1 ? "s " : " ") + joinNames(late) +
           " made no progress past step " + step + " within " + seconds(params_.step_timeout));
  return true;
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
      reached_ = reachedStep();
      reached_at_ = now;
      paused_since_ = now;
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
  if (phase_ != ClockPhase::kRunning) {
    return now;
  }
  const std::uint64_t reached = reachedStep();
  if (reached > reached_) {
    reached_ = reached;
    reached_at_ = now;
  }
  if (stop_requested_) {
    // The horizon is frozen; the run ends once everyone has finished the steps below it.
    if (reached_ >= horizon_ && fell_) {
      finish(StopKind::kFell, kExitFell, fell_->first, fell_->second);
      return now;
    }
    if (reached_ >= horizon_) {
      finish(StopKind::kRequested, kExitStopped, "",
             "stopped on request" + (stop_requested_by_.empty() ? std::string() : " of " + stop_requested_by_) +
                 (horizon_ > 0 ? " after step " + std::to_string(horizon_ - 1) : std::string(" before step 0")));
      return now;
    }
    return watchdogExpired(now) ? now : reached_at_ + params_.step_timeout;
  }
  if (paused_ && params_.max_pause && reached_ >= horizon_ && now >= paused_since_ + *params_.max_pause) {
    finish(StopKind::kRequested, kExitStopped, "",
           "paused for " + seconds(*params_.max_pause) + " and nobody resumed it (clock.max_pause_s); stopped " +
               (horizon_ > 0 ? "after step " + std::to_string(horizon_ - 1) : std::string("before step 0")));
    return now;
  }
  if (reached_ >= params_.end_step) {
    const auto release = pacedStart(anchor_, params_.end_step, params_.dt_ns, realtime_factor_);
    if (now < release) {
      return release;  // the last step lasts its dt on the wall clock too
    }
    finish(StopKind::kCompleted, kExitOk, "", "end of run after " + std::to_string(params_.end_step) + " steps");
    return now;
  }
  const std::uint64_t target = horizonTarget(now);
  // Grants in strides of W/2 (half the window is always left to run into), every step
  // when paced or single-stepping, and the last one at once.
  const std::uint64_t stride = std::max<std::uint64_t>(1, params_.window_steps / 2);
  if (target > horizon_ &&
      (horizon_ == 0 || target - horizon_ >= stride || target == params_.end_step || realtime_factor_ > 0.0 ||
       paused_ || reached_ >= horizon_)) {
    grant(target, now);
  }
  if (watchdogExpired(now)) {
    return now;
  }
  Time next = reached_ < horizon_ ? reached_at_ + params_.step_timeout : now + kIdlePoll;
  if (paused_ && horizon_ <= reached_) {
    // Observers (also late joiners of this best-effort topic) learn where the clock holds.
    if (now >= next_pause_announce_) {
      publishSimTime(true);
      next_pause_announce_ = now + kIdlePoll;
    }
    next = std::min(next, next_pause_announce_);
    if (params_.max_pause) {
      next = std::min(next, paused_since_ + *params_.max_pause);
    }
  } else {
    next_pause_announce_ = Time{};
  }
  if (realtime_factor_ > 0.0 && !paused_ && horizon_ < params_.end_step) {
    const auto release = pacedStart(anchor_, horizon_, params_.dt_ns, realtime_factor_);
    if (release > now) {
      next = std::min(next, release);  // the pace, not the window, holds the next step
    }
  }
  return next;
}

}  // namespace climbsim::clock
