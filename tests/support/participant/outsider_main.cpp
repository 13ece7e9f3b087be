/// climbsim-test-outsider: a DDS participant that is not part of the run and tries to steer
/// it, in every way an outsider could (the security system tests replay them). It is a
/// real Fast DDS participant of its own on the run's domain; it knows nothing but what it
/// reads there (RunStart with the run id, SimTime).
///
/// --stale-stop: at once, a latched Stop as an earlier run on a reused domain left it
/// (printed "stale stop published" on stdout once written, so a test can start the run after).
/// Then it waits for a RunStart and for SimTime to reach --attack-at-step, and sends, in order:
///  valves   ValveCommand claiming source "controller" for --valve-steps steps (all valves
///           closed), then one stamped step + 1000;
///  grant    a StepGrant of the run to its end, and a RunStart of another run;
///  failed   a StepDone FAILED claiming to be --victim, of the right run;
///  blame    a StepDone claiming --victim with a wrong run id (then the outsider leaves);
///  stop     a latched Stop FAILED of the right run;
///  control  ClockControl STOP, then PAUSE (never resumed) -- only with --control.
/// Each attack sent prints "sent <name>" on stdout; it exits 0 after --linger-ms.
///
/// --watch-s S (secured runs): only listens for S seconds (or until --until-file exists) to RunStart, SimTime and StepDone
/// and to discovery, then prints "participants_seen=N" (participant announcements, SPDP: in
/// the clear even in a secured run, as DDS Security specifies), "endpoints_seen=E" (readers
/// and writers discovered, SEDP), "samples_seen=M" and "unauthorized_participants=K" (DDS
/// Security handshakes that failed) and exits 0.
/// --only-write-stop: only creates a Stop writer and writes one Stop ("sent stop"): with the
/// identity of a participant whose permissions do not list clock/Stop it must be refused.
/// In a secured run it loads the identity CLIMBSIM_DDS_SECURITY_DIR/IDENTITY gives it.

#include <chrono>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <set>
#include <thread>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/topic_names.hpp"
#include "climbsim/dds_context.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "clockPubSubTypes.h"
#include "thermoPubSubTypes.h"

namespace {

using namespace climbsim;
using SteadyClock = std::chrono::steady_clock;

void said(const std::string& line) {
  std::cout << line << std::endl;  // flushed: the test reads it through a pipe
}

/// What discovery and the security handshakes tell a participant about the others.
class DiscoveryWatch : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    if (info.status == eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT) {
      std::lock_guard<std::mutex> lock(mutex_);
      seen_.insert(info.info.m_participantName.to_string());
    }
  }
  // Remote readers and writers only (Fast DDS tells of the participant's own too).
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* self,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    if (info.status == eprosima::fastrtps::rtps::WriterDiscoveryInfo::DISCOVERED_WRITER &&
        info.info.guid().guidPrefix != self->guid().guidPrefix) {
      std::lock_guard<std::mutex> lock(mutex_);
      topics_.insert(info.info.topicName().to_string());
      ++endpoints_;
    }
  }
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant* self,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override {
    if (info.status == eprosima::fastrtps::rtps::ReaderDiscoveryInfo::DISCOVERED_READER &&
        info.info.guid().guidPrefix != self->guid().guidPrefix) {
      std::lock_guard<std::mutex> lock(mutex_);
      topics_.insert(info.info.topicName().to_string());
      ++endpoints_;
    }
  }
#if HAVE_SECURITY
  void onParticipantAuthentication(eprosima::fastdds::dds::DomainParticipant*,
                                   eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override {
    if (info.status == eprosima::fastrtps::rtps::ParticipantAuthenticationInfo::UNAUTHORIZED_PARTICIPANT) {
      std::lock_guard<std::mutex> lock(mutex_);
      ++unauthorized_;
    }
  }
#endif
  std::set<std::string> seen() {
    std::lock_guard<std::mutex> lock(mutex_);
    return seen_;
  }
  int unauthorized() {
    std::lock_guard<std::mutex> lock(mutex_);
    return unauthorized_;
  }
  int endpoints() {
    std::lock_guard<std::mutex> lock(mutex_);
    return endpoints_;
  }
  std::set<std::string> topics() {
    std::lock_guard<std::mutex> lock(mutex_);
    return topics_;
  }

 private:
  std::mutex mutex_;
  std::set<std::string> seen_;
  std::set<std::string> topics_;
  int unauthorized_ = 0;
  int endpoints_ = 0;
};

/// --watch-s: listens, then says what it saw.
int watch(const DdsSettings& dds, double watch_s, const std::string& until_file) {
  Notifier notifier;
  DiscoveryWatch discovery;
  DdsContext context(dds, "outsider", &discovery);
  Reader<RunStartPubSubType> run_starts(context, topic::kRunStart, qos::kLatched, notifier);
  Reader<SimTimePubSubType> sim_time(context, topic::kSimTime, qos::kObserver, notifier);
  Reader<StepDonePubSubType> done(context, topic::kStepDone, qos::kControl, notifier);
  std::size_t samples = 0;
  const auto end = SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                            std::chrono::duration<double>(watch_s));
  while (SteadyClock::now() < end && (until_file.empty() || !std::filesystem::exists(until_file))) {
    const auto seen = notifier.generation();
    samples += run_starts.take().size() + sim_time.take().size() + done.take().size();
    notifier.waitChanged(seen, std::min(end, SteadyClock::now() + std::chrono::milliseconds(50)));
  }
  for (const auto& name : discovery.seen()) said("saw participant " + name);
  for (const auto& topic : discovery.topics()) said("saw an endpoint of topic " + topic);
  said("participants_seen=" + std::to_string(discovery.seen().size()));
  said("endpoints_seen=" + std::to_string(discovery.endpoints()));
  said("samples_seen=" + std::to_string(samples));
  said("unauthorized_participants=" + std::to_string(discovery.unauthorized()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-test-outsider: tries to steer a run it is not part of (security tests)"};
  DdsSettings dds;
  bool stale_stop = false;
  bool control = false;
  std::uint64_t attack_at = 50;
  std::uint64_t valve_steps = 40;
  std::string victim = "thermo";
  int linger_ms = 300;
  double timeout_s = 120.0;
  double watch_s = 0.0;
  std::string until_file;
  bool only_write_stop = false;
  dds.addOptions(app);
  app.add_flag("--stale-stop", stale_stop, "publish a latched Stop of an earlier run at once");
  app.add_flag("--control", control, "also send ClockControl STOP and PAUSE");
  app.add_option("--attack-at-step", attack_at, "attack once SimTime reaches this step");
  app.add_option("--valve-steps", valve_steps, "steps of forged ValveCommand samples");
  app.add_option("--victim", victim, "the participant the forged StepDone samples claim to be");
  app.add_option("--linger-ms", linger_ms, "stay this long after the last attack, then leave");
  app.add_option("--timeout-s", timeout_s, "give up (exit 1) if the run has not reached the step by then");
  app.add_option("--watch-s", watch_s, "only watch discovery and the clock's topics this long, then report");
  app.add_option("--until-file", until_file, "--watch-s: stop watching early once this file exists");
  app.add_flag("--only-write-stop", only_write_stop, "only write one Stop (a permissions test)");
  return guardedMain(app, argc, argv, "outsider", [&]() -> int {
    initLogging("outsider");
    dds.resolve();
    if (watch_s > 0.0) return watch(dds, watch_s, until_file);
    Notifier notifier;
    DdsContext context(dds, "outsider");
    if (only_write_stop) {
      Writer<StopPubSubType> stop(context, topic::kStop, qos::kLatched, notifier);
      Stop fake;
      fake.reason("the outsider stopped the run");
      stop.write(fake);
      said("sent stop");
      return 0;
    }
    Reader<RunStartPubSubType> run_starts(context, topic::kRunStart, qos::kLatched, notifier);
    Reader<SimTimePubSubType> sim_time(context, topic::kSimTime, qos::kObserver, notifier);
    Writer<StopPubSubType> stop(context, topic::kStop, qos::kLatched, notifier);
    Writer<RunStartPubSubType> run_start(context, topic::kRunStart, qos::kLatched, notifier);
    Writer<StepGrantPubSubType> grant(context, topic::kStepGrant, qos::kControl, notifier);
    Writer<StepDonePubSubType> done(context, topic::kStepDone, qos::kControl, notifier);
    Writer<ClockControlPubSubType> clock_control(context, topic::kClockControl, qos::kControl, notifier);
    Writer<ValveCommandPubSubType> valves(context, topic::kValveCommand, qos::kStepData, notifier);

    if (stale_stop) {
      Stop old;
      old.run_id(12345);
      old.last_step(0);
      old.kind(STOP_FAILED);
      old.culprit("drive");
      old.reason("a stale Stop of an earlier run (outsider)");
      stop.write(old);
      said("stale stop published");
    }

    const auto deadline = SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                                   std::chrono::duration<double>(timeout_s));
    std::optional<RunStart> started;
    std::uint64_t step = 0;
    // Waits for news; returns false at the deadline.
    auto poll = [&]() {
      const auto seen = notifier.generation();
      for (auto& r : run_starts.take()) {
        if (!started) started = r.data;
      }
      for (auto& r : sim_time.take()) step = std::max<std::uint64_t>(step, r.data.step());
      if (SteadyClock::now() >= deadline) return false;
      notifier.waitChanged(seen, std::min(deadline, SteadyClock::now() + std::chrono::milliseconds(50)));
      return true;
    };
    while (!started || step < attack_at) {
      if (!poll()) {
        spdlog::error("the run did not reach step {} within {} s", attack_at, timeout_s);
        return 1;
      }
    }
    const std::uint64_t run_id = started->run_id();
    spdlog::info("run {} at step {}: attacking", run_id, step);

    // Forged valve commands, one per step ahead of the run, as the controller would stamp them.
    ValveCommand forged;
    forged.source("controller");
    forged.opening().assign(7, 0.0);  // the default robot's chambers
    const std::uint64_t first = step;
    for (std::uint64_t k = first; k < first + valve_steps; ++k) {
      forged.step(k);
      forged.t_ns(static_cast<std::int64_t>(k) * started->dt_ns());
      valves.write(forged);
    }
    forged.step(first + 1000);
    valves.write(forged);
    said("sent valves");

    StepGrant all;
    all.run_id(run_id);
    all.horizon_step(started->end_step());
    all.dt_ns(started->dt_ns());
    grant.write(all);
    RunStart other = *started;
    other.run_id(run_id + 1);
    run_start.write(other);
    said("sent grant");

    StepDone failed;
    failed.participant(victim);
    failed.run_id(run_id);
    failed.progress_step(step);
    failed.kind(FAILED);
    failed.message("the outsider says " + victim + " failed");
    done.write(failed);
    said("sent failed");

    StepDone wrong = failed;
    wrong.run_id(run_id ^ 0x5a5a5a5a5a5a5a5aULL);
    wrong.kind(STEP_DONE);
    done.write(wrong);
    said("sent blame");

    Stop fake;
    fake.run_id(run_id);
    fake.last_step(step);
    fake.kind(STOP_FAILED);
    fake.culprit(victim);
    fake.reason("the outsider stopped the run");
    stop.write(fake);
    said("sent stop");

    if (control) {
      ClockControl command;
      command.sender("climbsim-clockctl");
      command.command(CLOCK_STOP);
      clock_control.write(command);
      command.command(CLOCK_PAUSE);
      clock_control.write(command);
      said("sent control");
    }
    // Reliable writers: let the samples reach every matched reader before leaving.
    done.waitAcknowledged(std::chrono::milliseconds(2000));
    clock_control.waitAcknowledged(std::chrono::milliseconds(2000));
    stop.waitAcknowledged(std::chrono::milliseconds(2000));
    std::this_thread::sleep_for(std::chrono::milliseconds(linger_ms));
    said("leaving");
    return 0;
  });
}
