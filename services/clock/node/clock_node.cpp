#include "clock_node.hpp"

#include <spdlog/spdlog.h>

#include <fastrtps/utils/IPLocator.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <set>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/topic_names.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/idl_hashes.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/names.hpp"
#include "climbsim/realtime_text.hpp"
#include "clock_translate.hpp"
#include "process_watch.hpp"

namespace climbsim::clock {

using SteadyClock = std::chrono::steady_clock;

namespace {
/// After the Stop, how long the clock waits for the participants to leave.
constexpr auto kLeaveGrace = std::chrono::seconds(3);
/// Longest single wait, so that a signal is noticed promptly.
constexpr auto kMaxWait = std::chrono::milliseconds(100);
/// How often the processes of this host's participants are looked at in /proc.
constexpr auto kWatchPeriod = std::chrono::milliseconds(100);
/// A participant's process stopped (SIGSTOP, a debugger) this long fails the run.
constexpr auto kStoppedLimit = std::chrono::seconds(1);
/// Progress lines at most this often.
constexpr auto kProgressPeriod = std::chrono::seconds(5);

}  // namespace

std::string lostWording(bool liveliness, const std::string& host, std::uint32_t pid) {
  const std::string dds = liveliness ? "liveliness lost" : "DDS dropped it";
  if (pid == 0 || !isThisHostName(host)) {
    return dds + (pid == 0 ? std::string() : ": its process " + std::to_string(pid) + " on " + host + " went silent");
  }
  const std::string process = "its process " + std::to_string(pid);
  const char state = processState(pid);
  if (processEnded(state)) return process + " exited";
  switch (state) {
    case 'T':
    case 't':
      return process + " is stopped (SIGSTOP or a debugger): it exists but does not run";
    default:
      return dds + "; " + process + " exists and runs but sends nothing";
  }
}

struct ClockNode::Endpoints {
  Endpoints(DdsContext& dds, Notifier& n)
      : ready(dds, topic::kParticipantReady, qos::kLatched, n),
        done(dds, topic::kStepDone, qos::kControl, n),
        control(dds, topic::kClockControl, qos::kControl, n),
        grant(dds, topic::kStepGrant, qos::kControl, n),
        run_start(dds, topic::kRunStart, qos::kLatched, n),
        stop(dds, topic::kStop, qos::kLatched, n),
        sim_time(dds, topic::kSimTime, qos::kObserver, n) {}

  Reader<climbsim::ParticipantReadyPubSubType> ready;
  Reader<climbsim::StepDonePubSubType> done;
  Reader<climbsim::ClockControlPubSubType> control;
  Writer<climbsim::StepGrantPubSubType> grant;
  Writer<climbsim::RunStartPubSubType> run_start;
  Writer<climbsim::StopPubSubType> stop;
  Writer<climbsim::SimTimePubSubType> sim_time;
  std::map<std::string, std::string> writer_to_participant;  ///< writerKey -> participant (checked senders only)
  /// Roster participant -> the DDS participant whose ParticipantReady the clock took first.
  std::map<std::string, ParticipantId> identity;
  /// Roster participant -> the host and pid its ParticipantReady gave (for the wording of a loss).
  std::map<std::string, std::pair<std::string, std::uint32_t>> process;
  /// The processes of the roster participants on this host (process_watch.hpp), looked at
  /// every kWatchPeriod.
  ProcessWatch watch;
  SteadyClock::time_point next_watch{};
  SenderLog dropped{"clock"};
  /// Participants whose processes the watch saw end or stop: they will not leave DDS before
  /// their lease runs out, and the clock does not wait for them to.
  std::set<std::string> gone;
};

/// Who the remote DDS participants are, from discovery: name and UDPv4 addresses by GUID
/// prefix (the clock checks a ClockControl sender against clock.control with them).
class ClockNode::Discovery : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  struct Peer {
    std::string name;
    std::vector<std::string> addresses;
  };

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    using Info = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& prefix = info.info.m_guid.guidPrefix;
    if (info.status != Info::DISCOVERED_PARTICIPANT && info.status != Info::CHANGED_QOS_PARTICIPANT) {
      peers_.erase(prefix);
      return;
    }
    Peer peer;
    peer.name = info.info.m_participantName.c_str();
    auto add = [&](const eprosima::fastrtps::rtps::RemoteLocatorList& list) {
      for (const auto& locator : list.unicast) {
        // A participant on the clock's machine announces only shared-memory locators.
        if (locator.kind != LOCATOR_KIND_UDPv4 && locator.kind != LOCATOR_KIND_SHM) continue;
        const std::string address = locator.kind == LOCATOR_KIND_SHM
                                        ? std::string(kSharedMemoryAddress)
                                        : eprosima::fastrtps::rtps::IPLocator::toIPv4string(locator);
        if (std::find(peer.addresses.begin(), peer.addresses.end(), address) == peer.addresses.end()) {
          peer.addresses.push_back(address);
        }
      }
    };
    add(info.info.metatraffic_locators);
    add(info.info.default_locators);
    peers_[prefix] = std::move(peer);
  }

  /// The participant with this prefix, if discovered.
  std::optional<Peer> peer(const ParticipantId& prefix) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto found = peers_.find(prefix);
    return found == peers_.end() ? std::nullopt : std::optional<Peer>(found->second);
  }

 private:
  mutable std::mutex mutex_;
  std::map<ParticipantId, Peer> peers_;
};

class ClockNode::Transport : public ClockTransport {
 public:
  Transport(Endpoints& e, climbsim::RobotShape robot) : e_(e), robot_(std::move(robot)) {}
  void publishRunStart(const RunStartMsg& msg) override {
    auto idl = toIdl(msg);
    idl.robot(robot_);
    for (const auto& entry : msg.roster) {
      climbsim::ParticipantIdentity id;
      id.participant(entry.participant);
      const auto bound = e_.identity.find(entry.participant);
      id.guid_prefix(bound == e_.identity.end() ? std::string() : participantIdHex(bound->second));
      idl.identities().push_back(id);
    }
    e_.run_start.write(idl);
    run_started = true;
  }
  void publishGrant(const GrantMsg& msg) override {
    auto idl = toIdl(msg);
    e_.grant.write(idl);
    ++grants;
  }
  void publishStop(const StopMsg& msg) override {
    auto idl = toIdl(msg);
    e_.stop.write(idl);
  }
  void publishSimTime(const SimTimeMsg& msg) override {
    auto idl = toIdl(msg);
    e_.sim_time.write(idl);
  }
  int grantReaders() const override { return e_.grant.matchedReaders(); }
  std::uint64_t grants = 0;
  bool run_started = false;  ///< RunStart was published

 private:
  Endpoints& e_;
  climbsim::RobotShape robot_;
};

ClockNode::ClockNode(const DdsSettings& dds, ClockParams params, climbsim::RobotShape robot)
    : params_(std::move(params)) {
  params_.validate();
  discovery_ = std::make_unique<Discovery>();
  dds_ = std::make_unique<DdsContext>(dds, "clock", discovery_.get());
  // A producer may run W steps ahead of a consumer: its samples wait in the step-data queues.
  const int depth = dds_->historyDepth(qos::kStepData);
  params_.max_window_steps = static_cast<std::uint32_t>(std::max(1, depth - 2));
  if (params_.window_steps > params_.max_window_steps) {
    throw ConfigError("--window-steps = " + std::to_string(params_.window_steps) + ": above " +
                      std::to_string(params_.max_window_steps) + ", the most the step-data queues hold (history depth " +
                      std::to_string(depth) + " of QoS profile '" + qos::kStepData + "' in " + dds.qos_file +
                      "); lower the window or deepen the queues");
  }
  for (const auto& [file, digest] : kIdlHashes) {
    params_.idl_hashes.emplace_back(file, digest);
  }
  endpoints_ = std::make_unique<Endpoints>(*dds_, notifier_);
  transport_ = std::make_unique<Transport>(*endpoints_, std::move(robot));
  core_ = std::make_unique<ClockCore>(params_, *transport_);
}

ClockNode::~ClockNode() {
  core_.reset();
  transport_.reset();
  endpoints_.reset();
  dds_.reset();
  discovery_.reset();
}

void ClockNode::feedEvents(ClockCore::Time now) {
  auto& e = *endpoints_;
  auto on_roster = [&](const std::string& name) {
    return std::find(params_.roster.begin(), params_.roster.end(), name) != params_.roster.end();
  };
  for (auto& r : e.ready.take()) {
    auto msg = fromIdl(r.data);
    const std::string& name = msg.entry.participant;
    // The first DDS participant to announce a roster name is that participant for the run;
    // only then is its writer remembered (the core refuses names off the roster, and a
    // second announcement of a name from another process).
    if (on_roster(name)) {
      const auto bound = e.identity.emplace(name, r.sender).first;
      if (bound->second == r.sender) {
        e.writer_to_participant[r.writer] = name;
        e.process[name] = {r.data.host().c_str(), r.data.pid()};
        if (onThisHost(r.sender, dds_->id(), r.data.host().c_str(), r.data.pid())) e.watch.watch(name, r.data.pid());
      }
    }
    core_->onReady(msg, now);
  }
  for (auto& r : e.done.take()) {
    auto msg = fromIdl(r.data);
    // Run id, roster and identity are checked before anything is recorded about the writer:
    // a foreign StepDone can neither fail nor advance the run, nor get a participant blamed
    // when its writer leaves.
    if (msg.run_id != params_.run_id) {
      e.dropped.drop(topic::kStepDone, r.writer,
                     "run id " + std::to_string(msg.run_id) + " is not this run's (claims '" + msg.participant + "')");
      continue;
    }
    const auto bound = e.identity.find(msg.participant);
    if (bound == e.identity.end() || !(bound->second == r.sender)) {
      e.dropped.drop(topic::kStepDone, r.writer,
                     "its DDS participant " + participantIdHex(r.sender) + " is not '" + msg.participant + "'" +
                         (bound == e.identity.end() ? " (not ready, or not on the roster)"
                                                    : " (that is " + participantIdHex(bound->second) + ")"));
      continue;
    }
    e.writer_to_participant[r.writer] = msg.participant;
    core_->onDone(msg, now);
  }
  for (auto& r : e.control.take()) {
    auto msg = fromIdl(r.data);
    if (params_.control_senders) {
      // Control is a privilege: the sending DDS participant (its discovered name and
      // addresses, not the sample's `sender` text) must be on clock.control.
      const auto peer = discovery_->peer(r.sender);
      const std::string why = peer ? controlRefusal(*params_.control_senders, peer->name, peer->addresses)
                                   : "its DDS participant " + participantIdHex(r.sender) + " was not discovered";
      if (!why.empty()) {
        e.dropped.drop(topic::kClockControl, r.writer, why + " (claims '" + msg.sender + "')");
        continue;
      }
      msg.sender = peer->name;
    }
    spdlog::info("control from '{}': command {}", msg.sender, static_cast<int>(msg.command));
    core_->onControl(msg, now);
  }
  // A process of this host that has ended is lost now, whatever DDS has noticed so far
  // (process_watch.hpp: after a kill -9 the leases of everybody may run out together).
  if (e.watch.size() > 0 && SteadyClock::now() >= e.next_watch) {
    e.next_watch = SteadyClock::now() + kWatchPeriod;
    for (const auto& [name, pid] : e.watch.ended()) {
      e.gone.insert(name);
      core_->onParticipantLost(name, "its process " + std::to_string(pid) + " exited", now);
    }
    // A stopped process is named by its state, not by the lease (which outlasts a loaded
    // machine's pauses: process_watch.hpp).
    for (const auto& [name, pid] : e.watch.stoppedFor(kStoppedLimit)) {
      e.gone.insert(name);
      core_->onParticipantLost(name, lostWording(false, e.process[name].first, pid), now);
    }
  }
  auto lost = e.ready.takeLost();
  auto lost_done = e.done.takeLost();
  lost.insert(lost.end(), lost_done.begin(), lost_done.end());
  for (const auto& l : lost) {
    auto who = e.writer_to_participant.find(l.writer);
    if (who != e.writer_to_participant.end()) {
      const auto proc = e.process.find(who->second);
      core_->onParticipantLost(who->second,
                               lostWording(l.liveliness, proc == e.process.end() ? std::string() : proc->second.first,
                                           proc == e.process.end() ? 0 : proc->second.second),
                               now);
    }
  }
}

void ClockNode::awaitParticipantsLeaving() {
  const auto deadline = SteadyClock::now() + kLeaveGrace;
  const auto gone = static_cast<int>(endpoints_->gone.size());
  while (endpoints_->done.matchedWriters() > gone && SteadyClock::now() < deadline) {
    const auto seen = notifier_.generation();
    notifier_.waitChanged(seen, std::min(deadline, SteadyClock::now() + kMaxWait));
  }
}

int ClockNode::run(const std::atomic<bool>& stop_signal) {
  const auto wall_start = SteadyClock::now();
  core_->start(wall_start);
  spdlog::info("waiting for the roster: {} participants, {} steps of {} ns, real-time factor {}", params_.roster.size(),
               params_.end_step, params_.dt_ns, params_.realtime_factor);
  auto next_progress = wall_start + kProgressPeriod;
  bool signalled = false;
  std::optional<SteadyClock::time_point> running_since;
  while (!core_->finished()) {
    const auto seen = notifier_.generation();
    const auto now = SteadyClock::now();
    feedEvents(now);
    if (core_->phase() != ClockPhase::kRunning && !core_->finished()) {
      // A participant the clock cannot authenticate never hears the clock: the clock gives the
      // start up itself (the participant does too, on its side of the pair).
      if (const auto stalled = dds_->stalledHandshake("clock", params_.roster)) {
        core_->onStartStalled(stalled->peer, stalled->reason);
      }
    }
    if (stop_signal.load() && !signalled) {
      signalled = true;
      ControlMsg stop;
      stop.command = ControlCommand::kStop;
      stop.sender = "a signal";
      core_->onControl(stop, now);
    }
    const auto next = core_->poll(now);
    if (!running_since && core_->phase() == ClockPhase::kRunning) {
      running_since = now;
      spdlog::info("roster complete, run started");
    }
    if (core_->finished()) {
      break;
    }
    if (now >= next_progress && core_->phase() == ClockPhase::kWaitingForReady) {
      next_progress = now + kProgressPeriod;
      spdlog::info("waiting for {}", joinNames(core_->missingReady()));
    } else if (now >= next_progress) {
      next_progress = now + kProgressPeriod;
      spdlog::info("step {} (t = {:.3f} s), horizon {}{}", core_->reachedStep(),
                   static_cast<double>(core_->reachedStep()) * static_cast<double>(params_.dt_ns) * 1e-9,
                   core_->horizon(), core_->paused() ? ", paused" : "");
    }
    if (next > now) {
      notifier_.waitChanged(seen, std::min(next, now + kMaxWait));
    }
  }
  const auto& stop = *core_->stopMessage();
  const double wall_s =
      std::chrono::duration<double>(SteadyClock::now() - running_since.value_or(SteadyClock::now())).count();
  const double sim_s = static_cast<double>(stop.t_ns) * 1e-9;
  if (stop.kind == StopKind::kFailed) {
    spdlog::error("run failed: {}", stop.reason);
  } else if (stop.kind == StopKind::kFell) {
    spdlog::warn("run ended early: {}", stop.reason);
  } else {
    spdlog::info("{}: {} steps, {:.3f} s simulated in {:.3f} s wall ({})", stop.reason, core_->horizon(), sim_s,
                 wall_s, realtimeText(sim_s, wall_s));
  }
  if (endpoints_->dropped.dropped() > 0) {
    spdlog::warn("dropped {} samples of senders that were not who they claimed", endpoints_->dropped.dropped());
  }
  statsAdd("deliveries", static_cast<double>(dds_->deliveries()));
  statsAdd("grants", static_cast<double>(transport_->grants));
  statsAdd("steps", static_cast<double>(core_->horizon()));
  writeStatsIfAsked("clock");
  leaveAfterResults("clock", core_->exitCode());
  if (transport_->run_started) {
    awaitParticipantsLeaving();
  } else {
    // Stopped before RunStart: the participants take that Stop only once this clock has left
    // (before RunStart they cannot tell it from a forged one), so leave once it is delivered.
    endpoints_->stop.waitAcknowledged(std::chrono::duration_cast<std::chrono::milliseconds>(kLeaveGrace));
  }
  return core_->exitCode();
}

}  // namespace climbsim::clock
