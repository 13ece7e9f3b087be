// Scenario files (deploy/scenarios/*.yaml): every shipped scenario loads and its robot file
// exists; bad keys and values give one line naming the file, the line, the key and the value.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/scenario.hpp"

namespace climbsim {
namespace {

const std::string kMinimal = R"(name: t
robot: ../robots/cromsci.yaml
scene: $BUILD/scenes/pylon.xml
start: {x_m: 1.0, y_m: 1.2, yaw_deg: -90}
duration_s: 10
controller: {type: reference, downforce_n: 2000}
drive:
  - {t_s: 0}
  - {t_s: 2, vx_mps: 0.05}
  - {t_s: 4, wz_radps: 0.1}
)";

/// The ConfigError message of parsing `text` (with `overrides`), or "" if it parsed.
std::string errorOf(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parseScenarioText(text, "/s/scenarios/x.yaml", overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, EveryShippedScenarioLoadsWithItsRobot) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CLIMBSIM_SCENARIOS_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const Scenario s = loadScenario(entry.path().string());
    EXPECT_EQ(s.name + ".yaml", entry.path().filename().string());
    EXPECT_NO_THROW(loadRobotDescription(s.robotPath()));
    ++count;
  }
  EXPECT_GE(count, 6);
}

TEST(Scenario, DefaultsAndHeldDriveValues) {
  const Scenario s = parseScenarioText(kMinimal, "/s/scenarios/x.yaml");
  EXPECT_EQ(s.step_ns, 5'000'000);
  EXPECT_EQ(s.depthPeriodSteps(), 4);   // 50 Hz at 200 Hz
  EXPECT_EQ(s.laserPeriodSteps(), 20);  // 10 Hz
  EXPECT_EQ(s.wall.kind, Scenario::WallKind::kVertical);
  EXPECT_EQ(s.controller.kind, Scenario::ControllerKind::kReference);
  EXPECT_DOUBLE_EQ(s.controller.downforce_n, 2000.0);
  // Keys left out keep the previous entry's value.
  EXPECT_DOUBLE_EQ(driveCommandAt(s.drive, 1'999'999'999).vx_mps, 0.0);
  EXPECT_DOUBLE_EQ(driveCommandAt(s.drive, 2'000'000'000).vx_mps, 0.05);
  EXPECT_DOUBLE_EQ(driveCommandAt(s.drive, 5'000'000'000).vx_mps, 0.05);
  EXPECT_DOUBLE_EQ(driveCommandAt(s.drive, 5'000'000'000).wz_radps, 0.1);
  EXPECT_EQ(s.start.hold_s, 0.0);
  EXPECT_DOUBLE_EQ(s.slide_limit_m, 0.005);
  EXPECT_DOUBLE_EQ(parseScenarioText(kMinimal, "/s/scenarios/x.yaml", {"slide_limit_m=0.02"}).slide_limit_m, 0.02);
  EXPECT_EQ(s.robotPath(), "/s/robots/cromsci.yaml");
  EXPECT_EQ(s.scenePath("/b"), "/b/scenes/pylon.xml");
}

TEST(Scenario, OverridesReplaceAndAddKeys) {
  const Scenario s = parseScenarioText(kMinimal, "/s/scenarios/x.yaml",
                                       {"duration_s=5", "controller.balance=false", "drive.1.vx_mps=0.02",
                                        "wall.orientation=floor"});
  EXPECT_DOUBLE_EQ(s.duration_s, 5.0);
  EXPECT_FALSE(s.controller.balance);
  EXPECT_DOUBLE_EQ(s.drive[1].vx_mps, 0.02);
  EXPECT_EQ(s.wall.kind, Scenario::WallKind::kFloor);
  // Shortening a scenario keeps its later entries; they are never reached.
  EXPECT_EQ(errorOf(kMinimal, {"duration_s=3.5"}), "");
}

TEST(Scenario, BadInputNamesFileLineKeyAndValue) {
  EXPECT_EQ(errorOf(kMinimal), "");
  struct Case {
    std::string from, to, expected;
  };
  const Case cases[] = {
      {"duration_s: 10", "duration_s: -1", "x.yaml:5: duration_s = -1"},
      {"yaw_deg: -90}", "yaw_deg: -90, hold_s: 1e6}", "start.hold_s = 1e6"},
      {"x_m: 1.0", "x_m: 18446744073709551616", "start.x_m = 18446744073709551616: it must be a number in [-1000, 1000]"},
      {"duration_s: 10", "duration_s: 10\nspeed: 3", "x.yaml:6: speed: unknown key"},
      {"type: reference", "type: magic", "controller.type = magic"},
      {"duration_s: 10", "duration_s: 10\nslide_limit_m: 0", "slide_limit_m = 0"},
      {"{t_s: 2, vx_mps: 0.05}", "{t_s: 2, vx_mps: nan}", "drive[1].vx_mps = nan"},
      {"{t_s: 2, vx_mps: 0.05}", "{t_s: 0, vx_mps: 0.05}", "drive[1].t_s = 0: times must increase"},
      {"duration_s: 10", "duration_s: 10\nrates: {depth_hz: 33}", "rates.depth_hz = 33"},
      {"duration_s: 10", "duration_s: 10\nfaults: [{t_s: 1, kind: valve_stuck, chamber: 9, opening: 0.5}]",
       "faults[0].chamber = 9"},
      {"duration_s: 10", "duration_s: 10\nwall: {orientation: overhang}", "wall.overhang_deg: missing"},
      {"duration_s: 10", "duration_s: 10\nwall: {wheels_on: sand}",
       "x.yaml:6: wall.wheels_on = sand: it must be plane or surface"},
      {"{type: reference, downforce_n: 2000}", "{type: fixed, valves: [0, 0, 0, 2, 0, 0, 0]}",
       "controller.valves[3] = 2"},
  };
  for (const auto& c : cases) {
    std::string text = kMinimal;
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    const std::string message = errorOf(text);
    EXPECT_NE(message.find(c.expected), std::string::npos) << "got: " << message << "\nexpected: " << c.expected;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_NE(errorOf(kMinimal, {"nokey"}).find("--set nokey: expected key=value"), std::string::npos);
  EXPECT_NE(errorOf(kMinimal, {"bogus=1"}).find("x.yaml (--set bogus=1): bogus: unknown key"), std::string::npos);
  EXPECT_NE(errorOf(kMinimal, {"controller.type=bad"}).find("(--set controller.type=bad): controller.type = bad"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal, {"drive.7.t_s=1"}).find("--set drive.7.t_s"), std::string::npos);
  // A hold longer than a shortened run is no error: `--set duration_s=...` shortens any scenario
  // (docs/scenario-files.md#keys, start.hold_s).
  EXPECT_EQ(errorOf(kMinimal, {"start.hold_s=2", "duration_s=0.01"}), "");
  // A long bad value is cut in the message.
  const std::string long_value = errorOf(kMinimal, {"duration_s=" + std::string(100000, 'a')});
  EXPECT_LT(long_value.size(), 300u) << long_value.size();
}

TEST(Scenario, EndOnTakesFallAndSealOverNothingAsBooleans) {
  const Scenario defaults = parseScenarioText(kMinimal, "/s/scenarios/x.yaml");
  EXPECT_TRUE(defaults.end_on.fall);
  EXPECT_FALSE(defaults.end_on.seal_over_nothing) << "a seal over nothing warns by default";
  const Scenario set = parseScenarioText(kMinimal + "end_on: {fall: false, seal_over_nothing: true}\n", "x.yaml");
  EXPECT_FALSE(set.end_on.fall);
  EXPECT_TRUE(set.end_on.seal_over_nothing);
  EXPECT_TRUE(parseScenarioText(kMinimal + "end_on: {fall: true}\n", "x.yaml", {"end_on.seal_over_nothing=true"})
                  .end_on.seal_over_nothing);
  EXPECT_EQ(errorOf(kMinimal + "end_on: {seal_over_nothing: maybe}\n"),
            "/s/scenarios/x.yaml:11: end_on.seal_over_nothing = maybe: it must be true or false");
  EXPECT_NE(errorOf(kMinimal + "end_on: {seal_over_void: true}\n").find("seal_over_void: unknown key"),
            std::string::npos);
}

TEST(Scenario, TheDepthCameraTakesSidesUpToWhatItsTopicHolds) {
  EXPECT_EQ(parseScenarioText(kMinimal, "x.yaml", {"depth_camera.size_px=2048"}).depth_camera.size_px, 2048);
  EXPECT_EQ(Scenario::DepthCamera::kMaxSizePx, 2048);
  const std::string too_large = errorOf(kMinimal, {"depth_camera.size_px=2049"});
  EXPECT_NE(too_large.find("depth_camera.size_px = 2049"), std::string::npos) << too_large;
  EXPECT_NE(too_large.find("2048"), std::string::npos) << too_large;
  EXPECT_NE(errorOf(kMinimal, {"depth_camera.size_px=0"}).find("depth_camera.size_px = 0"), std::string::npos);
}

TEST(Scenario, AMegabyteOverrideIsOneShortLineNamingTheKey) {
  // 1 MB passes no execve (one argument may hold 128 KiB), but a launcher-internal caller or a
  // 100 KiB value can bring it here: refused before it is parsed or copied anywhere.
  const std::string value(1 << 20, '7');
  const std::string message = errorOf(kMinimal, {"name=" + value});
  EXPECT_NE(message.find("--set name=...: " + std::to_string(value.size() + 5) + " characters, at most 4096"),
            std::string::npos)
      << message.substr(0, 300);
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_LT(message.size(), 200u);
  // A long key is cut as well; a value at the limit is still parsed as usual.
  EXPECT_LT(errorOf(kMinimal, {std::string(200000, 'k') + "=1"}).size(), 200u);
  EXPECT_EQ(errorOf(kMinimal, {"name=" + std::string(4091, 'n')}), "");
}

TEST(Scenario, TheCrackOfTheGeneratedPylonIsAKeyWithItsRanges) {
  const Scenario plain = parseScenarioText(kMinimal, "/s/scenarios/x.yaml");
  EXPECT_FALSE(plain.crack.has_value()) << "no crack key: the build's scene as it is";
  // --set creates the mapping; the key left out keeps the shipped pylon's value.
  const Scenario deep = parseScenarioText(kMinimal, "/s/scenarios/x.yaml", {"crack.depth_m=0.005"});
  ASSERT_TRUE(deep.crack.has_value());
  EXPECT_EQ(deep.crack->depth_m, 0.005);
  EXPECT_EQ(deep.crack->width_m, Scenario::Crack::kDefaultWidth_m);
  const Scenario both = parseScenarioText(kMinimal + "crack: {depth_m: 0.02, width_m: 0.03}\n", "/s/scenarios/x.yaml");
  ASSERT_TRUE(both.crack.has_value());
  EXPECT_EQ(both.crack->depth_m, 0.02);
  EXPECT_EQ(both.crack->width_m, 0.03);

  // Line 11 is the appended crack key: each bad value names the file, line, key and value.
  EXPECT_NE(errorOf(kMinimal + "crack: {depth_m: 0}\n").find("x.yaml:11: crack.depth_m = 0: it must be"),
            std::string::npos)
      << errorOf(kMinimal + "crack: {depth_m: 0}\n");
  EXPECT_NE(errorOf(kMinimal + "crack: {width_m: 0.6}\n").find("x.yaml:11: crack.width_m = 0.6: it must be a number in (0, 0.5]"),
            std::string::npos)
      << errorOf(kMinimal + "crack: {width_m: 0.6}\n");
  EXPECT_NE(errorOf(kMinimal + "crack: {depth: 0.01}\n").find("x.yaml:11: crack.depth: unknown key"), std::string::npos)
      << errorOf(kMinimal + "crack: {depth: 0.01}\n");
  EXPECT_NE(errorOf(kMinimal, {"crack.depth_m=deep"}).find("(--set crack.depth_m=deep): crack.depth_m = deep"),
            std::string::npos)
      << errorOf(kMinimal, {"crack.depth_m=deep"});
  // Only the generated pylon has this crack; a scene of one's own is refused, naming the --set.
  const std::string other = errorOf(kMinimal, {"scene=../scenes/flat.xml", "crack.depth_m=0.01"});
  EXPECT_NE(other.find("(--set crack.depth_m=0.01): crack = {depth_m: 0.01}: only the generated pylon (scene: "
                       "$BUILD/scenes/pylon.xml) has this crack; scene is '../scenes/flat.xml'"),
            std::string::npos)
      << other;
  EXPECT_EQ(std::count(other.begin(), other.end(), '\n'), 0) << other;
}

TEST(Scenario, TheResolvedCopyOfACrackNamesTheRunsSceneAndRunsAgainAsItIs) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("climbsim-crack-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "scenarios");
  const std::string path = (dir / "scenarios" / "x.yaml").string();
  std::ofstream(path) << kMinimal;
  const std::string run_scene = (dir / "run" / "scene" / "pylon.xml").string();

  // Without a crack: no run scene, the build's; with one: the run's, and crack is left out.
  const std::string plain = resolvedScenarioText(path, {}, "/b");
  EXPECT_NE(plain.find("scene: /b/scenes/pylon.xml"), std::string::npos) << plain;
  EXPECT_THROW(resolvedScenarioText(path, {}, "/b", run_scene), ConfigError) << "a scene nobody asked for";
  EXPECT_THROW(resolvedScenarioText(path, {"crack.depth_m=0.005"}, "/b"), ConfigError) << "the crack needs its scene";
  const std::string text = resolvedScenarioText(path, {"crack.depth_m=0.005"}, "/b", run_scene);
  EXPECT_NE(text.find("# crack: {depth_m: 0.005, width_m: 0.01}: the pylon generated for this run"), std::string::npos)
      << text;
  EXPECT_NE(text.find("scene: " + run_scene), std::string::npos) << text;
  const std::string copy = (dir / "run" / "scenario.yaml").string();
  std::filesystem::create_directories(dir / "run");
  std::ofstream(copy) << text;
  const Scenario again = loadScenario(copy);
  EXPECT_FALSE(again.crack.has_value());
  EXPECT_EQ(again.scenePath("/elsewhere"), run_scene);
  std::filesystem::remove_all(dir);
}

TEST(Scenario, SwitchingTheControllerFromTheCommandLineIgnoresTheFilesSetPointWithOneNote) {
  // The file's reference controller has downforce_n: 2000 (line 6). --set controller.type=none
  // switches it off: the set-point means nothing then, and the user should not have to edit the file.
  const Scenario none = parseScenarioText(kMinimal, "/s/scenarios/x.yaml", {"controller.type=none"});
  EXPECT_EQ(none.controller.kind, Scenario::ControllerKind::kNone);
  ASSERT_EQ(none.ignored.size(), 1u);
  EXPECT_EQ(none.ignored[0],
            "/s/scenarios/x.yaml:6: controller.downforce_n = 2000 is ignored: --set controller.type=none takes no "
            "set-point (only a reference controller does)");
  EXPECT_EQ(parseScenarioText(kMinimal, "/s/scenarios/x.yaml", {"controller.type=external"}).ignored.size(), 1u);
  // No override of the type: nothing ignored; a file that contradicts itself is still refused.
  EXPECT_TRUE(parseScenarioText(kMinimal, "/s/scenarios/x.yaml").ignored.empty());
  std::string contradiction = kMinimal;
  contradiction.replace(contradiction.find("type: reference"), 15, "type: none");
  EXPECT_NE(errorOf(contradiction).find("controller.downforce_n = 2000: only the reference controller takes a set-point"),
            std::string::npos);
  // Both from the command line: the user asked for both, which contradict each other.
  EXPECT_NE(errorOf(kMinimal, {"controller.type=none", "controller.downforce_n=1500"}).find("controller.downforce_n"),
            std::string::npos);
  // A fixed controller's valves, switched to the reference controller: ignored likewise.
  std::string fixed = kMinimal;
  fixed.replace(fixed.find("{type: reference, downforce_n: 2000}"), 36, "{type: fixed, valves: [1, 1, 1, 1, 1, 1, 1]}");
  const Scenario reference = parseScenarioText(fixed, "/s/scenarios/x.yaml", {"controller.type=reference"});
  EXPECT_EQ(reference.controller.kind, Scenario::ControllerKind::kReference);
  ASSERT_EQ(reference.ignored.size(), 1u);
  EXPECT_NE(reference.ignored[0].find("controller.valves = [1, 1, 1, 1, 1, 1, 1] is ignored"), std::string::npos)
      << reference.ignored[0];
  // Switched to fixed without valves: the valves are missing, as in a file.
  EXPECT_NE(errorOf(kMinimal, {"controller.type=fixed"}).find("controller.valves: missing"), std::string::npos);

  // The run's resolved copy leaves the key out: every service reads it without the override.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("climbsim-none-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "scenarios");
  const std::string path = (dir / "scenarios" / "x.yaml").string();
  std::ofstream(path) << kMinimal;
  const std::string text = resolvedScenarioText(path, {"controller.type=none"}, "/b");
  EXPECT_EQ(text.find("downforce_n"), std::string::npos) << text;
  const Scenario copy = parseScenarioText(text, (dir / "scenario.yaml").string());
  EXPECT_EQ(copy.controller.kind, Scenario::ControllerKind::kNone);
  EXPECT_TRUE(copy.ignored.empty());
  std::filesystem::remove_all(dir);
}

TEST(Scenario, ARecordedControllerNamesTheRecordingItPlaysBackAnchoredAtTheScenarioFile) {
  // controller.commands: the run.mcap whose commands a recorded controller plays back; a
  // relative path is taken against the scenario file's folder, as the robot's is.
  const auto recorded = [](const std::string& controller) {
    std::string text = kMinimal;
    text.replace(text.find("{type: reference, downforce_n: 2000}"), 36, controller);
    return text;
  };
  const Scenario s = parseScenarioText(recorded("{type: recorded, commands: ../runs/a/run.mcap}"), "/s/scenarios/x.yaml");
  EXPECT_EQ(s.controller.kind, Scenario::ControllerKind::kRecorded);
  EXPECT_EQ(s.controller.commands_file, "/s/runs/a/run.mcap");
  EXPECT_EQ(parseScenarioText(recorded("{type: recorded, commands: /r/run.mcap}"), "/s/scenarios/x.yaml")
                .controller.commands_file,
            "/r/run.mcap");
  EXPECT_STREQ(toString(s.controller.kind), "recorded");
  // Without the recording, or with it for another type: one line naming the key.
  EXPECT_NE(errorOf(recorded("{type: recorded}")).find("x.yaml:6: controller.commands: missing"), std::string::npos)
      << errorOf(recorded("{type: recorded}"));
  EXPECT_NE(errorOf(recorded("{type: none, commands: a.mcap}"))
                .find("controller.commands = a.mcap: only a recorded controller takes recorded commands"),
            std::string::npos)
      << errorOf(recorded("{type: none, commands: a.mcap}"));
  // Switched away from recorded on the command line: the file's recording is ignored with a note.
  const Scenario reference = parseScenarioText(recorded("{type: recorded, commands: a.mcap}"), "/s/scenarios/x.yaml",
                                               {"controller.type=reference"});
  ASSERT_EQ(reference.ignored.size(), 1u);
  EXPECT_NE(reference.ignored[0].find("controller.commands = a.mcap is ignored"), std::string::npos)
      << reference.ignored[0];
  // recording.commands: off unless asked for.
  EXPECT_FALSE(parseScenarioText(kMinimal, "/s/scenarios/x.yaml").recording.commands);
  EXPECT_TRUE(parseScenarioText(kMinimal, "/s/scenarios/x.yaml", {"recording.commands=true"}).recording.commands);
  EXPECT_NE(errorOf(kMinimal, {"recording.commands=maybe"}).find("recording.commands"), std::string::npos);

  // The run's resolved copy names the recording by its absolute path.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("climbsim-rec-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "scenarios");
  const std::string path = (dir / "scenarios" / "x.yaml").string();
  std::ofstream(path) << recorded("{type: recorded, commands: ../a/run.mcap}");
  const Scenario copy = parseScenarioText(resolvedScenarioText(path, {}, "/b"), "/elsewhere/scenario.yaml");
  EXPECT_EQ(copy.controller.commands_file, (dir / "a" / "run.mcap").string());
  std::filesystem::remove_all(dir);
}

TEST(Scenario, EveryProblemIsReportedAtOnceInLineOrder) {
  std::string text = kMinimal;
  text.replace(text.find("duration_s: 10"), 14, "duration_s: -1\nspeed: 3");
  text.replace(text.find("type: reference"), 15, "type: magic");
  const std::string message = errorOf(text);
  std::vector<int> lines;
  std::istringstream in(message);
  for (std::string line; std::getline(in, line);) {
    ASSERT_EQ(line.rfind("/s/scenarios/x.yaml:", 0), 0u) << message;
    lines.push_back(std::atoi(line.c_str() + std::string("/s/scenarios/x.yaml:").size()));
  }
  ASSERT_EQ(lines.size(), 3u) << message;
  EXPECT_TRUE(std::is_sorted(lines.begin(), lines.end())) << message;
  EXPECT_NE(message.find("duration_s = -1"), std::string::npos) << message;
  EXPECT_NE(message.find("speed: unknown key"), std::string::npos) << message;
  EXPECT_NE(message.find("controller.type = magic"), std::string::npos) << message;
}

}  // namespace
}  // namespace climbsim
