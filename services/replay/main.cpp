/// climbsim-replay: plays recorded samples back on the lockstep (docs/recordings.md#replay). A
/// roster member that takes a recorded producer's name and schedule (--name thermo) and writes
/// that producer's samples of the recorded topics (RUN_DIR/run.mcap, --recording) at their own
/// steps, with their initial states, so that they travel byte for byte as recorded: a
/// controller under test runs open-loop against them. --topics narrows the topics played.

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <memory>
#include <set>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/service_command_line.hpp"
#include "climbsim/topic_names.hpp"
#include "node/replayed_topic.hpp"
#include "robotPubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"

int main(int argc, char** argv) {
  using namespace climbsim;
  ServiceCommandLine cli("climbsim-replay: plays a recorded producer's samples back on the lockstep",
                         "scenario file (the run's scenario.yaml; read for --set only)", "duration_s=5");
  const char* env_recording = std::getenv("CLIMBSIM_REPLAY_RECORDING");
  const char* env_topics = std::getenv("CLIMBSIM_REPLAY_TOPICS");
  std::string recording = env_recording ? env_recording : "";
  std::string topics = env_topics ? env_topics : "";
  cli.app.add_option("--recording", recording, "the recording (RUN_DIR/run.mcap; default $CLIMBSIM_REPLAY_RECORDING)");
  cli.app.add_option("--topics", topics, "topics to play, comma-separated (default $CLIMBSIM_REPLAY_TOPICS, or all "
                                         "that --name produced among the recorded ones)");
  return cli.run(argc, argv, "replay", [&]() -> int {
    initLogging(cli.participant.name);
    if (recording.empty()) throw ConfigError("--recording: none given (nor CLIMBSIM_REPLAY_RECORDING)");
    const std::set<std::string> known = {topic::kChamberState, topic::kAdhesionForce, topic::kLeakage,
                                         topic::kRobotState, topic::kDriveState};
    std::set<std::string> wanted = topics.empty() ? known : recording::topicList(topics);
    for (const auto& t : wanted) {
      if (!known.count(t)) throw ConfigError("--topics: '" + t + "' is no topic a replay plays");
    }
    const auto messages = recording::readRecordedMessages(recording, wanted);
    LockstepParticipant participant(cli.participant);
    std::vector<std::unique_ptr<replay::ReplayedPort>> ports;
    const auto add = [&](const char* t, auto type) {
      using PubSubT = decltype(type);
      if (!wanted.count(t)) return;
      auto port = std::make_unique<replay::ReplayedTopic<PubSubT>>(participant, t, messages.at(t));
      if (port->plays()) ports.push_back(std::move(port));
    };
    add(topic::kChamberState, ChamberStatePubSubType{});
    add(topic::kAdhesionForce, AdhesionForcePubSubType{});
    add(topic::kLeakage, LeakagePubSubType{});
    add(topic::kRobotState, RobotStatePubSubType{});
    add(topic::kDriveState, DriveStatePubSubType{});
    // A producer with nothing to play (--topics left its topics out) stays on the roster idle.
    if (ports.empty()) spdlog::info("replay: no sample of '{}' on the topics played", participant.name());
    const int code = participant.run([&](const StepContext& ctx) {
      for (auto& port : ports) port->write(ctx);
    });
    std::uint64_t played = 0;
    for (const auto& port : ports) played += port->played();
    spdlog::info("replay: {} samples of {} played", played, recording);
    leaveAfterResults(participant.name().c_str(), code);
    return code;
  });
}
