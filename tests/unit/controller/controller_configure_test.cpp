// climbsim-controller's one configuration path (services/controller/configure.hpp): its main
// (and --print-config) and climbsim solo both take the command model's parameters from
// configureController; they are the scenario's controller section and drive schedule with the
// robot's controller parameters.

#include <gtest/gtest.h>
#include <unistd.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <filesystem>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/recording/mcap_run_file.hpp"
#include "climbsim/topic_names.hpp"
#include "clockPubSubTypes.h"
#include "controller/configure.hpp"
#include "thermoPubSubTypes.h"

namespace climbsim::controller {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;

TEST(ControllerConfigure, MainAndSoloGetTheSameParamsFromAScenario) {
  for (const char* name : {"crack-descent", "valve-stuck", "figure9"}) {
    const std::string file = kScenarios + "/" + name + ".yaml";
    const ControllerParams main_params = configureController(loadScenarioAndRobot(file, {}));
    const ControllerParams solo_params = configureController(scenarioAndRobot(loadScenario(file)));
    EXPECT_EQ(main_params.kind, solo_params.kind) << name;
    EXPECT_EQ(main_params.engine_count, solo_params.engine_count) << name;
    EXPECT_EQ(main_params.drive.size(), solo_params.drive.size()) << name;
    EXPECT_EQ(main_params.reference.desired_downforce_n, solo_params.reference.desired_downforce_n) << name;
  }
}

TEST(ControllerConfigure, TheScenariosControllerAndScheduleAnOverrideChangesItsKey) {
  const std::string file = kScenarios + "/crack-descent.yaml";  // reference at 2200 N, two drive entries
  const ScenarioAndRobot run = loadScenarioAndRobot(file, {});
  const ControllerParams params = configureController(run);
  EXPECT_EQ(params.kind, Scenario::ControllerKind::kReference);
  EXPECT_EQ(params.reference.desired_downforce_n, 2200.0);
  ASSERT_EQ(params.drive.size(), 2u);
  EXPECT_EQ(params.drive[1].vx_mps, 0.05);
  const ControllerParams lower = configureController(loadScenarioAndRobot(file, {"controller.downforce_n=1800"}));
  EXPECT_EQ(lower.reference.desired_downforce_n, 1800.0);
  EXPECT_EQ(lower.kind, params.kind);
  EXPECT_EQ(lower.drive.size(), params.drive.size());
  EXPECT_EQ(lower.engine_count, params.engine_count);
}

/// Writes `sample` to `channel` of `file` at t_ns, serialised as a DDS writer does.
template <class PubSubT, class Sample>
void writeSample(recording::McapRunFile& file, std::uint16_t channel, std::int64_t t_ns, Sample sample) {
  PubSubT type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  ASSERT_TRUE(type.serialize(&sample, &payload));
  file.write(channel, t_ns, payload.data, payload.length);
}

ValveCommand valveCommand(const std::string& source, std::int64_t t_ns, std::vector<double> opening) {
  ValveCommand v;
  v.source(source);
  v.step(static_cast<std::uint64_t>(t_ns / 5'000'000));
  v.t_ns(t_ns);
  v.opening(opening);
  v.downforce_setpoint_n(2200.0);
  return v;
}

/// A run.mcap holding `valves` on controller/ValveCommand (no such channel when empty) and, when
/// stop_ns >= 0, the clock's Stop at stop_ns.
std::string recordingWith(const std::string& name, const std::vector<ValveCommand>& valves, std::int64_t stop_ns) {
  const auto dir = std::filesystem::temp_directory_path() / ("climbsim-recorded-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / (name + ".mcap")).string();
  recording::McapRunFile file(path);
  if (!valves.empty()) {
    const auto channel = file.addCdrChannel(topic::kValveCommand, "climbsim::ValveCommand");
    for (const auto& v : valves) writeSample<ValveCommandPubSubType>(file, channel, v.t_ns(), v);
  }
  const auto stop_channel = file.addCdrChannel(topic::kStop, "climbsim::Stop");
  if (stop_ns >= 0) {
    Stop stop;
    stop.t_ns(stop_ns);
    writeSample<StopPubSubType>(file, stop_channel, stop_ns, stop);
  }
  file.close();
  return path;
}

/// The ConfigError of configuring crack-descent (2 s) with a recorded controller playing `file`.
std::string errorOfRecorded(const std::string& file) {
  try {
    configureController(loadScenarioAndRobot(kScenarios + "/crack-descent.yaml",
                                             {"controller.type=recorded", "controller.commands=" + file,
                                              "duration_s=2"}));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ControllerConfigure, ARecordedControllerReadsTheRecordedValveCommandsInOrder) {
  const std::vector<double> half(7, 0.5), open(7, 1.0);
  const std::string file = recordingWith("good", {valveCommand("controller", 0, half),
                                                   valveCommand("controller", 1'000'000'000, open)},
                                         2'000'000'000);
  const ControllerParams params = configureController(loadScenarioAndRobot(
      kScenarios + "/crack-descent.yaml", {"controller.type=recorded", "controller.commands=" + file, "duration_s=2"}));
  EXPECT_EQ(params.kind, Scenario::ControllerKind::kRecorded);
  ASSERT_EQ(params.recorded.valves.size(), 2u);
  EXPECT_EQ(params.recorded.valves[1].t_ns, 1'000'000'000);
  EXPECT_EQ(params.recorded.valves[1].opening, open);
  EXPECT_EQ(params.recorded.valves[0].downforce_setpoint_n, 2200.0);
  EXPECT_TRUE(params.recorded.engines.empty());
  EXPECT_EQ(params.recorded.end_ns, 2'000'000'000);
  EXPECT_EQ(errorOfRecorded(file), "");
}

TEST(ControllerConfigure, ARecordingARecordedControllerCannotPlayIsOneLineNamingTheFileAndWhy) {
  const std::vector<double> half(7, 0.5);
  const auto expectError = [](const std::string& file, const std::string& part) {
    const std::string message = errorOfRecorded(file);
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expectError("/nonexistent/run.mcap", "/nonexistent/run.mcap");
  expectError(recordingWith("no-commands", {}, 2'000'000'000), "record the run with recording.commands: true");
  expectError(recordingWith("short", {valveCommand("controller", 0, half)}, 1'000'000'000),
              "the recorded run stopped at 1 s, this run lasts 2 s");
  expectError(recordingWith("six-valves", {valveCommand("controller", 0, std::vector<double>(6, 0.5))}, 2'000'000'000),
              "controller/ValveCommand at t = 0 s has 6 openings, the robot has 7 valves");
  expectError(recordingWith("out-of-range", {valveCommand("controller", 0, {0.5, 0.5, 1.5, 0.5, 0.5, 0.5, 0.5})},
                            2'000'000'000),
              "openings[2] = 1.5 (must be in [0, 1])");
  expectError(recordingWith("two-writers", {valveCommand("controller", 0, half), valveCommand("py", 5'000'000, half)},
                            2'000'000'000),
              "two writers, 'controller' and 'py'");
  expectError(recordingWith("backwards", {valveCommand("controller", 10'000'000, half),
                                          valveCommand("controller", 5'000'000, half)},
                            2'000'000'000),
              "goes back in time, from 0.01 s to 0.005 s");
  expectError(recordingWith("no-stop", {valveCommand("controller", 0, half)}, -1), "no clock/Stop message");
  std::filesystem::remove_all(std::filesystem::path(recordingWith("x", {}, 0)).parent_path());
}

TEST(ControllerConfigure, AScenarioIsNeeded) {
  EXPECT_THROW(configureController(loadScenarioAndRobot("", {})), ConfigError);
}

}  // namespace
}  // namespace climbsim::controller
