#include "climbsim/lockstep_participant.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <set>

#include "climbsim/topic_names.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/idl_hashes.hpp"
#include "climbsim/names.hpp"
#include "climbsim/run_id_env.hpp"
#include "climbsim/run_stats.hpp"

namespace climbsim {

using SteadyClock = std::chrono::steady_clock;

namespace {
/// After a failure, how long to wait for the clock's Stop so that the failure, not the
/// disappearance, is what the clock reports.
constexpr auto kFailureLinger = std::chrono::seconds(2);

std::string hostName() {
  char buffer[256] = {0};
  if (gethostname(buffer, sizeof(buffer) - 1) != 0) {
    return "unknown";
  }
  return buffer;
}

std::optional<std::uint64_t> runIdFromEnvironment() {
  const char* value = std::getenv(kEnvRunId);
  if (value == nullptr || *value == '\0') {
    return std::nullopt;
  }
  char* end = nullptr;
  errno = 0;
  const unsigned long long id = std::strtoull(value, &end, 10);
  if (errno != 0 || end == value || *end != '\0' || *value == '-') {
    throw ConfigError(std::string(kEnvRunId) + " = '" + value + "': not a run id (an unsigned 64-bit number)");
  }
  return id;
}

SteadyClock::time_point deadlineAfter(double seconds) {
  return SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
}
}  // namespace

void ParticipantOptions::addOptions(CLI::App& app) {
  app.add_option("--name", name, "participant name on the clock's roster")->required();
  app.add_option("--period", schedule.period_steps, "due every PERIOD clock steps (>= 1)");
  app.add_option("--offset", schedule.offset_steps, "first due step (< period)");
  app.add_option("--start-timeout-s", start_timeout_s, "give up if the run has not started after this long");
  dds.addOptions(app);
}

void ParticipantOptions::resolve() {
  validateName("--name", name);
  schedule.validate("participant '" + name + "'");
  if (!(start_timeout_s > 0.0)) {
    throw ConfigError("--start-timeout-s = " + std::to_string(start_timeout_s) + "; it must be > 0");
  }
  dds.resolve();
}

LockstepParticipant::LockstepParticipant(const ParticipantOptions& options)
    : options_(options), dropped_(options.name) {
  options_.resolve();
  expected_run_id_ = runIdFromEnvironment();
  dds_ = std::make_unique<DdsContext>(options_.dds, options_.name);
  grant_reader_ = std::make_unique<Reader<StepGrantPubSubType>>(*dds_, topic::kStepGrant, qos::kControl, notifier_);
  run_start_reader_ = std::make_unique<Reader<RunStartPubSubType>>(*dds_, topic::kRunStart, qos::kLatched, notifier_);
  stop_reader_ = std::make_unique<Reader<StopPubSubType>>(*dds_, topic::kStop, qos::kLatched, notifier_);
  done_writer_ = std::make_unique<Writer<StepDonePubSubType>>(*dds_, topic::kStepDone, qos::kControl, notifier_);
  ready_writer_ =
      std::make_unique<Writer<ParticipantReadyPubSubType>>(*dds_, topic::kParticipantReady, qos::kLatched, notifier_);
  batch_writer_ = std::make_unique<Writer<RecordBatchPubSubType>>(*dds_, topic::kRecordBatch, qos::kRecord, notifier_);
  observer_writer_ =
      std::make_unique<Writer<RecordBatchPubSubType>>(*dds_, topic::kObserverBatch, qos::kRecordObserver, notifier_);
}

LockstepParticipant::~LockstepParticipant() {
  inputs_.clear();
  outputs_.clear();
}

void LockstepParticipant::takeRunStart(const Received<RunStart>& r) {
  if (run_start_) {
    if (!(r.sender == *clock_id_ && r.data.run_id() == run_start_->run_id())) {
      dropForeign(topic::kRunStart, r.writer,
                  "run " + std::to_string(r.data.run_id()) + " from DDS participant " + participantIdHex(r.sender) +
                      ", after this run's clock started it");
    }
    return;
  }
  if (expected_run_id_ && r.data.run_id() != *expected_run_id_) {
    dropForeign(topic::kRunStart, r.writer,
                "run id " + std::to_string(r.data.run_id()) + " is not this run's (" + kEnvRunId + " = " +
                    std::to_string(*expected_run_id_) + ")");
    return;
  }
  // The clock bound every roster participant to the DDS participant that announced it; a
  // RunStart that does not, or binds us to another, is not our clock's.
  std::map<std::string, ParticipantId> identities;
  for (const auto& id : r.data.identities()) {
    if (const auto prefix = participantIdFromHex(id.guid_prefix().c_str())) {
      identities.emplace(id.participant().c_str(), *prefix);
    }
  }
  for (const auto& entry : r.data.roster()) {
    const auto found = identities.find(entry.participant().c_str());
    const std::string why = found == identities.end() ? "it names no DDS participant for '" + std::string(entry.participant()) + "'"
                            : entry.participant() == options_.name && !(found->second == dds_->id())
                                ? "it binds '" + options_.name + "' to another DDS participant (" +
                                      participantIdHex(found->second) + ")"
                                : std::string();
    if (!why.empty()) {
      dropForeign(topic::kRunStart, r.writer, "run " + std::to_string(r.data.run_id()) + ": " + why);
      return;
    }
  }
  run_start_ = r.data;
  clock_id_ = r.sender;
  identities_ = std::move(identities);
  for (const auto& entry : run_start_->roster()) {
    for (const auto& topic : entry.output_topics()) {
      producer_ids_[topic.c_str()].push_back({entry.participant().c_str(), identities_.at(entry.participant().c_str())});
    }
  }
}

void LockstepParticipant::takeStop(const Received<Stop>& r) {
  if (stop_) {
    return;
  }
  if (run_start_) {
    if (r.sender == *clock_id_ && r.data.run_id() == run_start_->run_id()) {
      stop_ = r.data;
    } else {
      dropForeign(topic::kStop, r.writer,
                  "run " + std::to_string(r.data.run_id()) + " from DDS participant " + participantIdHex(r.sender) +
                      ", not this run's clock");
    }
    return;
  }
  // Before RunStart nobody is bound as the clock, and a Stop of this run's id may be forged
  // (the id is in the RunStart anyone on the domain reads): judged once the RunStart binds the
  // clock, or taken when the clock leaves without one (takeStopOfUnstartedRun).
  if (early_stops_.size() < 64) {
    early_stops_.push_back(r);
  }
}

void LockstepParticipant::takeStopOfUnstartedRun() {
  if (stop_ || run_start_ || !clock_lost_ || !expected_run_id_) {
    return;
  }
  // The clock left without starting the run: it never published a RunStart, so the run id
  // was never public, and a Stop of that id is its (e.g. a bad roster).
  for (const auto& r : early_stops_) {
    if (r.data.run_id() == *expected_run_id_) {
      stop_ = r.data;
      return;
    }
  }
}

void LockstepParticipant::pollControl() {
  for (auto& r : run_start_reader_->take()) {
    takeRunStart(r);
  }
  if (run_start_ && !early_stops_.empty()) {
    for (const auto& r : early_stops_) {
      takeStop(r);
    }
    early_stops_.clear();
  }
  for (auto& r : stop_reader_->take()) {
    takeStop(r);
  }
  for (auto& r : grant_reader_->take()) {
    if (!run_start_) {
      continue;
    }
    if (r.sender == *clock_id_ && r.data.run_id() == run_start_->run_id()) {
      horizon_ = std::max<std::uint64_t>(horizon_, r.data.horizon_step());
    } else {
      dropForeign(topic::kStepGrant, r.writer,
                  "run " + std::to_string(r.data.run_id()) + " from DDS participant " + participantIdHex(r.sender) +
                      ", not this run's clock");
    }
  }
  if (!clock_seen_ && grant_reader_->matchedWriters() > 0) {
    clock_seen_ = true;  // a status call per step is not free: ask only until the clock is seen
  }
  for (const auto& lost : grant_reader_->takeLost()) {
    // Only the clock of this run leaving counts (an outsider's grant writer may come and go);
    // before the run start, when no grant writer is left.
    if (clock_seen_ && (clock_id_ ? lost.sender == *clock_id_ : grant_reader_->matchedWriters() == 0)) {
      clock_lost_ = true;
    }
  }
  takeStopOfUnstartedRun();
  for (auto& input : inputs_) {
    input->drain();
  }
  drainRecords();
}

const std::vector<detail::ProducerIdentity>* LockstepParticipant::producerIdentities(const std::string& topic) const {
  static const std::vector<detail::ProducerIdentity> kNobody;
  if (!run_start_) {
    return nullptr;
  }
  const auto found = producer_ids_.find(topic);
  return found == producer_ids_.end() ? &kNobody : &found->second;
}

void LockstepParticipant::drainRecords() {
  if (!batch_reader_) {
    return;
  }
  if (!run_start_) {
    return;  // before the run start nobody's identity is known: the batches wait in the reader
  }
  for (auto& r : batch_reader_->take()) {
    const std::string source = r.data.source().c_str();
    const auto who = identities_.find(source);
    if (r.data.run_id() != run_start_->run_id() || who == identities_.end() || !(who->second == r.sender)) {
      dropForeign(topic::kRecordBatch, r.writer,
                  "claims to be '" + source + "' of run " + std::to_string(r.data.run_id()) + " from DDS participant " +
                      participantIdHex(r.sender));
      continue;
    }
    for (const auto& sample : r.data.samples()) {
      for (auto& port : recorded_) {
        if (port->topic() == sample.topic().c_str()) {
          if (r.data.initial()) {
            port->acceptInitial(source, sample.cdr());
          } else {
            port->accept(source, sample.cdr());
          }
        }
      }
    }
    if (r.data.initial()) {
      initial_from_.insert(source);
    }
  }
}

void LockstepParticipant::recordInitial(const std::string& topic,
                                        const eprosima::fastrtps::rtps::SerializedPayload_t& cdr) {
  if (run_start_) {
    throw std::logic_error("topic '" + topic + "': the initial state is given before run()");
  }
  if (cdr.length > 65536) {
    throw std::runtime_error("topic '" + topic + "': an initial state of " + std::to_string(cdr.length) +
                             " bytes is too large for a record batch (65536)");
  }
  initial_records_[topic].assign(cdr.data, cdr.data + cdr.length);
}

void LockstepParticipant::sendInitialRecords() {
  if (recorder_names_.empty()) {
    return;
  }
  // Sent even without any initial state: a recorder waits for it before its row 0.
  RecordBatch initial;
  initial.source(options_.name);
  initial.run_id(run_start_->run_id());
  initial.first_step(0);
  initial.end_step(0);
  initial.initial(true);
  for (const auto& [topic, cdr] : initial_records_) {
    if (recorded_outputs_.count(topic) == 0) {
      continue;
    }
    RecordedSample sample;
    sample.topic(topic);
    sample.step(0);
    sample.cdr() = cdr;
    initial.samples().push_back(std::move(sample));
  }
  batch_writer_->write(initial);
  statsAdd("record_batches", 1.0);
}

void LockstepParticipant::record(const std::string& topic, std::uint64_t step,
                                 const eprosima::fastrtps::rtps::SerializedPayload_t& cdr) {
  if (cdr.length > 65536) {
    throw std::runtime_error("topic '" + topic + "': a sample of " + std::to_string(cdr.length) +
                             " bytes is too large for a record batch (65536)");
  }
  if (batch_.samples().size() >= 4096) {
    flushRecords();
  }
  RecordedSample sample;
  sample.topic(topic);
  sample.step(step);
  sample.cdr().assign(cdr.data, cdr.data + cdr.length);
  batch_.samples().push_back(std::move(sample));
}

void LockstepParticipant::flushRecords() {
  if (batch_.samples().empty()) {
    return;
  }
  batch_.source(options_.name);
  batch_.run_id(run_start_ ? run_start_->run_id() : 0);
  batch_.end_step(progress_);
  batch_writer_->write(batch_);
  statsAdd("record_batches", 1.0);
  // Observers (the viewer) get the newest of each topic, at most 30 times a second, and only
  // while one is matched: without one the feed costs nothing.
  if (observer_writer_->matchedReaders() > 0) observer_feed_.add(batch_);
  batch_.samples().clear();
  batch_.first_step(progress_);
  flushObservers(false);
}

void LockstepParticipant::flushObservers(bool force) {
  if (!observer_feed_.pending()) {
    return;  // the usual case in a wait: no clock read
  }
  const auto now = SteadyClock::now();
  if (!force && !observer_feed_.due(now)) {
    return;
  }
  auto batch = observer_feed_.take(now, options_.name, run_start_ ? run_start_->run_id() : 0, progress_);
  observer_writer_->write(batch);
  statsAdd("observer_batches", 1.0);
}

void LockstepParticipant::reportProgress() {
  flushRecords();
  if (progress_ > acked_) {
    sendDone(progress_, STEP_DONE, "");
    acked_ = progress_;
    statsAdd("acks", 1.0);
  }
  last_report_ = SteadyClock::now();
}

bool LockstepParticipant::stampIsRead(const std::string& topic, std::uint64_t step) const {
  const auto found = consumers_.find(topic);
  if (found == consumers_.end()) {
    return false;
  }
  // Our sample stamped `step` is held until our next due step: a consumer reads it at
  // its due steps in (step, step + period] (lag 1) or [step, step + period) (lag 0).
  const std::uint64_t period = options_.schedule.period_steps;
  for (const auto& consumer : found->second) {
    const std::uint64_t first = consumer.lag == InputLag::kSameStep ? step : step + 1;
    const std::uint64_t due = consumer.schedule.nextDueFrom(first);
    if (due < first + period && due < end_step_) {
      return true;
    }
  }
  return false;
}

void LockstepParticipant::planOutputs() {
  consumers_.clear();
  recorded_outputs_.clear();
  recorder_names_.clear();
  std::set<std::string> mine;
  for (const auto& output : outputs_) {
    mine.insert(output->topic());
  }
  for (const auto& entry : run_start_->roster()) {
    const Schedule schedule{entry.period_steps(), entry.offset_steps()};
    const auto& same = entry.same_step_inputs();
    for (const auto& t : entry.input_topics()) {
      const std::string topic = t.c_str();
      if (mine.count(topic) == 0) continue;
      const bool lag0 = std::any_of(same.begin(), same.end(), [&](const auto& s) { return topic == s.c_str(); });
      consumers_[topic].push_back({schedule, lag0 ? InputLag::kSameStep : InputLag::kOneStep});
    }
    bool records_mine = false;
    for (const auto& t : entry.recorded_topics()) {
      if (mine.count(t.c_str()) != 0) {
        recorded_outputs_.insert(t.c_str());
        records_mine = true;
      }
    }
    if (records_mine) recorder_names_.push_back(entry.participant().c_str());
  }
}

void LockstepParticipant::waitForNews(std::uint64_t seen_generation) {
  if (run_start_ && (progress_ > acked_ || !batch_.samples().empty()) &&
      SteadyClock::now() - last_report_ > kSlowWait) {
    reportProgress();  // whoever waits long says how far it got: the watchdog blames the right one
  }
  pollControl();
  if (stop_) {
    flushObservers(true);  // the run's last states, whenever the previous batch went
    throw RunEnded{exitCodeForStop(*stop_)};
  }
  flushObservers(false);  // what a pause or a slow step held back
  if (clock_lost_) {
    spdlog::error("the clock vanished (its liveliness was lost) without stopping the run");
    throw RunEnded{kExitFailed};
  }
  // Bounded wait: liveliness changes also notify, this is only a safety net.
  notifier_.waitChanged(seen_generation, SteadyClock::now() + std::chrono::milliseconds(200));
}

void LockstepParticipant::waitUntil(const std::function<bool()>& condition, SteadyClock::time_point deadline,
                                    const std::string& what) {
  while (true) {
    const auto seen = notifier_.generation();
    pollControl();
    if (condition()) {
      return;
    }
    if (SteadyClock::now() >= deadline) {
      throw std::runtime_error("timed out after " + std::to_string(options_.start_timeout_s) + " s waiting for " + what);
    }
    waitForNews(seen);
  }
}

int LockstepParticipant::exitCodeForStop(const Stop& stop) const {
  switch (stop.kind()) {
    case STOP_COMPLETED:
      spdlog::info("run completed at step {}", stop.last_step());
      return kExitOk;
    case STOP_REQUESTED:
      spdlog::info("run stopped on request after step {}: {}", stop.last_step(), stop.reason().c_str());
      return kExitOk;
    case STOP_FELL:
      spdlog::warn("run ended after step {}: {}", stop.last_step(), stop.reason().c_str());
      return kExitOk;
    case STOP_FAILED:
    default:
      spdlog::error("run failed{}: {}",
                    stop.culprit().size() > 0 ? std::string(" because of '") + stop.culprit().c_str() + "'" : "",
                    stop.reason().c_str());
      return kExitFailed;
  }
}

void LockstepParticipant::checkHandshakes(const std::vector<std::string>& peers) const {
  if (const auto stalled = dds_->stalledHandshake(options_.name, peers)) {
    throw RetryableStartError(stalled->reason);
  }
}

void LockstepParticipant::announceReady() {
  ParticipantReady ready;
  ready.participant(options_.name);
  RosterEntry entry;
  entry.participant(options_.name);
  entry.period_steps(options_.schedule.period_steps);
  entry.offset_steps(options_.schedule.offset_steps);
  for (const auto& input : inputs_) {
    entry.input_topics().push_back(input->topic());
  }
  for (const auto& output : outputs_) {
    entry.output_topics().push_back(output->topic());
  }
  for (const auto& input : inputs_) {
    if (input->lag() == InputLag::kSameStep) {
      entry.same_step_inputs().push_back(input->topic());
    }
  }
  for (const auto& recorded : recorded_) {
    entry.recorded_topics().push_back(recorded->topic());
  }
  for (const auto& input : inputs_) {
    for (const auto& producer : input->from()) {
      entry.input_sources().push_back(input->topic() + "=" + producer);
    }
  }
  ready.entry(entry);
  for (const auto& [file, digest] : kIdlHashes) {
    IdlHash hash;
    hash.file(file);
    hash.sha256(digest);
    ready.idl_hashes().push_back(hash);
  }
  ready.host(hostName().substr(0, kMaxNameLength));
  ready.pid(static_cast<std::uint32_t>(getpid()));
  ready_writer_->write(ready);
}

std::vector<std::pair<std::string, Schedule>> LockstepParticipant::producersOf(const std::string& topic) const {
  std::vector<std::pair<std::string, Schedule>> producers;
  if (!run_start_) {
    return producers;
  }
  for (const auto& entry : run_start_->roster()) {
    const auto& outs = entry.output_topics();
    if (std::any_of(outs.begin(), outs.end(), [&](const auto& t) { return topic == t.c_str(); })) {
      producers.emplace_back(entry.participant().c_str(), Schedule{entry.period_steps(), entry.offset_steps()});
    }
  }
  std::sort(producers.begin(), producers.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return producers;
}

void LockstepParticipant::armDataEndpoints(SteadyClock::time_point deadline) {
  const auto& roster = run_start_->roster();
  const bool on_roster = std::any_of(roster.begin(), roster.end(), [&](const RosterEntry& e) {
    return options_.name == e.participant().c_str();
  });
  if (!on_roster) {
    throw std::runtime_error("the run started without '" + options_.name + "' on its roster");
  }
  // Consumers of this participant's samples of `topic`: those reading every producer of it,
  // and those reading it from this one (input_sources "topic=name").
  auto consumersOf = [&](const std::string& topic) {
    std::vector<std::string> names;
    const std::string prefix = topic + "=";
    for (const auto& entry : roster) {
      const auto& reads = entry.input_topics();
      if (std::none_of(reads.begin(), reads.end(), [&](const auto& t) { return topic == t.c_str(); })) {
        continue;
      }
      bool selective = false;
      bool selects_me = false;
      for (const auto& s : entry.input_sources()) {
        const std::string source = s.c_str();
        if (source.compare(0, prefix.size(), prefix) == 0) {
          selective = true;
          selects_me = selects_me || source.substr(prefix.size()) == options_.name;
        }
      }
      if (!selective || selects_me) names.push_back(entry.participant().c_str());
    }
    return names;
  };
  for (const auto& input : inputs_) {
    const auto producers = producersOf(input->topic());
    for (const auto& wanted : input->from()) {
      if (std::none_of(producers.begin(), producers.end(), [&](const auto& p) { return p.first == wanted; })) {
        std::string names;
        for (const auto& p : producers) names += (names.empty() ? "" : ", ") + p.first;
        throw ConfigError("'" + options_.name + "' reads topic '" + input->topic() + "' from '" + wanted +
                          "', which is not a producer of it on the roster (producers: " +
                          (names.empty() ? "none" : names) + ")");
      }
    }
  }
  planOutputs();
  // Recorders read one batch topic from every producer of what they record.
  std::set<std::string> batch_producers;
  for (const auto& recorded : recorded_) {
    for (const auto& [producer, schedule] : producersOf(recorded->topic())) {
      batch_producers.insert(producer);
    }
  }
  std::vector<std::string> roster_names;
  for (const auto& [name, id] : identities_) roster_names.push_back(name);
  // Who each endpoint waits for: the producers an input reads, the consumers an output feeds,
  // the clock, the recorders of the outputs and the producers of the recorded topics (every
  // name is on the roster, so identities_ has it).
  auto idsOf = [&](const std::vector<std::string>& names) {
    std::vector<ParticipantId> ids;
    for (const auto& name : names) ids.push_back(identities_.at(name));
    return ids;
  };
  std::vector<std::pair<const detail::InputPort*, std::vector<ParticipantId>>> input_waits;
  for (const auto& input : inputs_) {
    std::vector<std::string> names = input->from();
    if (names.empty()) {
      for (const auto& p : producersOf(input->topic())) names.push_back(p.first);
    }
    input_waits.emplace_back(input.get(), idsOf(names));
  }
  std::vector<std::pair<const detail::OutputPort*, std::vector<ParticipantId>>> output_waits;
  for (const auto& output : outputs_) output_waits.emplace_back(output.get(), idsOf(consumersOf(output->topic())));
  const std::vector<ParticipantId> clock{*clock_id_};
  const auto recorders = idsOf(recorder_names_);
  const auto batch_producer_ids = idsOf(std::vector<std::string>(batch_producers.begin(), batch_producers.end()));
  // Matched by identity, not counted: a writer or reader of the topic that is not on the
  // roster (an outsider's, a plain DDS observer's) must not stand in for a roster member whose
  // endpoint has not matched yet, or that member misses the first samples (VOLATILE) and the
  // run waits for them until the watchdog. An endpoint whose matching events did not tell
  // every participant (MatchedEndpoints) falls back to the count.
  auto allMatched = [](const std::optional<std::vector<ParticipantId>>& matched, int count,
                       const std::vector<ParticipantId>& wanted) {
    if (!matched) return count >= static_cast<int>(wanted.size());
    return std::all_of(wanted.begin(), wanted.end(), [&](const ParticipantId& id) {
      return std::find(matched->begin(), matched->end(), id) != matched->end();
    });
  };
  waitUntil(
      [&] {
        checkHandshakes(roster_names);
        // The clock, too: its StepDone reader must have matched before ARMED is written.
        if (!allMatched(grant_reader_->matchedParticipants(), grant_reader_->matchedWriters(), clock) ||
            !allMatched(done_writer_->matchedParticipants(), done_writer_->matchedReaders(), clock)) {
          return false;
        }
        for (const auto& [input, ids] : input_waits) {
          if (!allMatched(input->matchedParticipants(), input->matchedWriters(), ids)) return false;
        }
        for (const auto& [output, ids] : output_waits) {
          if (!allMatched(output->matchedParticipants(), output->matchedReaders(), ids)) return false;
        }
        if (!allMatched(batch_writer_->matchedParticipants(), batch_writer_->matchedReaders(), recorders)) {
          return false;
        }
        return !batch_reader_ || allMatched(batch_reader_->matchedParticipants(), batch_reader_->matchedWriters(),
                                            batch_producer_ids);
      },
      deadline, "the data topics to match their producers and consumers");
}

void LockstepParticipant::sendDone(std::uint64_t step, StepDoneKind kind, const std::string& message) {
  StepDone done;
  done.participant(options_.name);
  done.run_id(run_start_ ? run_start_->run_id() : 0);
  done.progress_step(step);
  done.kind(kind);
  done.message(message.substr(0, 255));
  done_writer_->write(done);
}

void LockstepParticipant::reportFell(const std::string& reason) {
  if (fell_reported_) {
    return;
  }
  fell_reported_ = true;
  spdlog::warn("{}", reason);
  sendDone(current_step_.value_or(progress_), FELL, reason);
}

void LockstepParticipant::awaitStop() {
  const auto deadline = SteadyClock::now() + kFailureLinger;
  while (!stop_ && !clock_lost_ && SteadyClock::now() < deadline) {
    const auto seen = notifier_.generation();
    pollControl();
    if (stop_) {
      break;
    }
    notifier_.waitChanged(seen, std::min(deadline, SteadyClock::now() + std::chrono::milliseconds(100)));
  }
}

void LockstepParticipant::failRun(const std::string& message) {
  // The clock's reason names the step ("participant 'x' failed at step N: ..."): the message
  // sent carries none of its own; the local log line has it.
  if (current_step_) {
    spdlog::error("step {}: {}", *current_step_, message);
  } else {
    spdlog::error("{}", message);
  }
  try {
    sendDone(current_step_.value_or(progress_), FAILED, message);
    awaitStop();
  } catch (const std::exception& e) {
    spdlog::error("could not report the failure to the clock: {}", e.what());
  }
}

int LockstepParticipant::run(const StepFn& step) {
  const auto deadline = deadlineAfter(options_.start_timeout_s);
  if (!recorded_.empty() && !batch_reader_) {
    batch_reader_ =
        std::make_unique<Reader<RecordBatchPubSubType>>(*dds_, topic::kRecordBatch, qos::kRecord, notifier_);
  }
  std::uint64_t steps_computed = 0;
  double step_cpu_s = 0.0;
  // The process's CPU (every thread) from the run's first step to its end: what the run itself
  // costs the machine, start-up (scene loading, discovery) left out.
  std::optional<double> run_cpu_start_s;
  auto write_stats = [&] {
    if (run_cpu_start_s) statsAdd("run_cpu_s", processCpuSeconds() - *run_cpu_start_s);
    if (dropped_.dropped() > 0) {
      spdlog::warn("dropped {} samples of senders that were not who they claimed", dropped_.dropped());
    }
    statsAdd("deliveries", static_cast<double>(dds_->deliveries()));
    statsAdd("steps_computed", static_cast<double>(steps_computed));
    statsAdd("step_cpu_s", step_cpu_s);
    writeStatsIfAsked(options_.name);
  };
  try {
    waitUntil(
        [&] {
          checkHandshakes({"clock"});
          return grant_reader_->matchedWriters() > 0 && done_writer_->matchedReaders() > 0;
        },
        deadline, "the clock on domain " + std::to_string(options_.dds.domain_id));
    announceReady();
    spdlog::info("ready (period {} offset {}), waiting for the run to start", options_.schedule.period_steps,
                 options_.schedule.offset_steps);
    waitUntil([&] { return run_start_.has_value(); }, deadline, "the run to start");
    armDataEndpoints(deadline);
    sendInitialRecords();
    end_step_ = run_start_->end_step();
    ack_stride_ = std::max<std::uint64_t>(1, run_start_->window_steps() / 2);
    progress_ = std::min(options_.schedule.nextDueFrom(0), end_step_);
    acked_ = progress_;
    batch_.first_step(progress_);
    last_report_ = SteadyClock::now();
    sendDone(0, ARMED, "");
    run_cpu_start_s = processCpuSeconds();
    const std::int64_t dt_ns = run_start_->dt_ns();
    while (true) {
      const auto seen = notifier_.generation();
      pollControl();
      if (!stop_ && progress_ < horizon_ && progress_ < end_step_) {
        const std::uint64_t k = progress_;
        current_step_ = k;
        const double cpu_before = threadCpuSeconds();
        step(StepContext{k, static_cast<std::int64_t>(k) * dt_ns, dt_ns});
        step_cpu_s += threadCpuSeconds() - cpu_before;
        current_step_.reset();
        ++steps_computed;
        progress_ = std::min(options_.schedule.nextDueFrom(k + 1), end_step_);
        if (progress_ - acked_ >= ack_stride_) {
          reportProgress();
        }
        continue;
      }
      reportProgress();  // at the horizon (or stopped): say so, and wait for more
      waitForNews(seen);
    }
  } catch (const RunEnded& ended) {
    write_stats();
    return ended.exit_code;
  } catch (const RetryableStartError& e) {
    if (run_start_) {
      failRun(e.what());  // the clock stops the run naming it
    } else {
      spdlog::error("{}", e.what());  // no clock to tell: this process's exit ends the start
    }
    write_stats();
    return kExitRetryStart;
  } catch (const ConfigError& e) {
    failRun(e.what());
    write_stats();
    return kExitConfig;
  } catch (const std::exception& e) {
    failRun(e.what());
    write_stats();
    return kExitFailed;
  }
}

}  // namespace climbsim
