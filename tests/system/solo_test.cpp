// The in-process reference run (climbsim-solo) against the distributed run (`climbsim-compose
// run`, every service a process on real Fast DDS): the same scenario must give the same
// trace.csv, byte for byte. And `climbsim-sweep` over solo and distributed variants.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "launcher_run.hpp"
#include "shipped_scenarios.hpp"

namespace {

using namespace climbsim::system_test;

TEST(Solo, EveryShippedScenarioGivesTheSameTraceSoloAndDistributed) {
  // Every scenario of deploy/scenarios, a check run each (shipped_scenarios.hpp: the hold, the
  // release and the first metres), three ways: solo, distributed at the default window and
  // distributed at W = 1 (the classic one-grant-per-step lockstep). The stamped data are the
  // promise, the window only bounds the run-ahead: one trace, byte for byte.
  const auto scenarios = shippedScenarios();
  ASSERT_GE(scenarios.size(), 10u);
  for (const auto& scenario : scenarios) {
    const std::string args = checkArgs(scenario);
    const auto solo = runTool("climbsim-solo", "solo-" + scenario.name, args);
    ASSERT_EQ(solo.exit_code, 0) << args << "\n" << solo.output;
    const auto distributed = runScenario("distributed-" + scenario.name, args);
    ASSERT_EQ(distributed.exit_code, 0) << args << "\n" << distributed.output;
    const auto lockstep = runScenario("window1-" + scenario.name, args + " --window-steps 1");
    ASSERT_EQ(lockstep.exit_code, 0) << args << "\n" << lockstep.output;
    const std::string a = readFile(solo.dir / "trace.csv");
    EXPECT_EQ(lineCount(a), checkRows(scenario) + 1) << args << ": a header and a row per step";
    EXPECT_EQ(a.find("nan"), std::string::npos) << args << ": a NaN cell (row 0 holds the initial states)";
    EXPECT_TRUE(a == readFile(distributed.dir / "trace.csv")) << args << ": solo and distributed traces differ";
    EXPECT_TRUE(a == readFile(lockstep.dir / "trace.csv")) << args << ": solo and distributed at W = 1 differ";
    EXPECT_EQ(readFile(solo.dir / "scenario.yaml"), readFile(distributed.dir / "scenario.yaml")) << args;
  }
}

TEST(Solo, SubpixelLeakageGivesTheSameTraceSoloAndDistributedAndChangesTheLeakOverTheCrack) {
  // depth_camera.subpixel: the scene and the sealing take it from the one scenario key, in one
  // process as in separate ones. Over the crack (from 4.6 s) the leak areas differ from the
  // pixel centres' run (the option off); before it they need not.
  const std::string args = "crack-descent --set duration_s=6";
  const auto solo = runTool("climbsim-solo", "solo-subpixel", args + " --set depth_camera.subpixel=true");
  ASSERT_EQ(solo.exit_code, 0) << solo.output;
  const auto distributed = runScenario("distributed-subpixel", args + " --set depth_camera.subpixel=true");
  ASSERT_EQ(distributed.exit_code, 0) << distributed.output;
  const std::string a = readFile(solo.dir / "trace.csv");
  EXPECT_EQ(lineCount(a), 1201u) << "a header and a row per step";
  EXPECT_TRUE(a == readFile(distributed.dir / "trace.csv")) << "solo and distributed traces differ";
  const auto centres = runTool("climbsim-solo", "solo-pixel-centres", args + " --set depth_camera.subpixel=false");
  ASSERT_EQ(centres.exit_code, 0) << centres.output;
  EXPECT_FALSE(a == readFile(centres.dir / "trace.csv")) << "depth_camera.subpixel changed nothing";
}

TEST(Solo, WritesTheRunDirectoryOfARun) {
  const auto r = runTool("climbsim-solo", "solo-run-dir", "crack-descent --set duration_s=6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string summary = readFile(r.dir / "summary.json");
  EXPECT_NE(summary.find("\"completed\": true"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"steps\": 1200"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"realtime_factor\""), std::string::npos) << summary;
  for (const char* plot : {"downforce.png", "pressures.png", "valves.png", "wheel_loads.png", "ring_5s.png"}) {
    EXPECT_GT(fs::exists(r.dir / "plots" / plot) ? fs::file_size(r.dir / "plots" / plot) : 0u, 1000u) << plot;
  }
  EXPECT_TRUE(fs::exists(r.dir / "pictures" / "sealing_gaps_5s.png"));
  EXPECT_TRUE(fs::exists(r.dir / "pictures" / "sealing_edges_1s.png"));
}

TEST(Solo, AFallEndsTheRunWithTheDistributedRunsOutcomeAndTrace) {
  const std::string args = "crack-descent --set duration_s=6 --set 'controller={type: none}'";
  const auto solo = runTool("climbsim-solo", "solo-fall", args);
  EXPECT_EQ(solo.exit_code, 5) << solo.output;
  EXPECT_NE(solo.output.find("FELL at t = 2."), std::string::npos) << solo.output;
  const std::string summary = readFile(solo.dir / "summary.json");
  EXPECT_NE(summary.find("\"outcome\": \"fell\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"culprit\": \"drive\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"fell\": true"), std::string::npos) << summary;
  const auto distributed = runScenario("distributed-fall", args);
  EXPECT_EQ(distributed.exit_code, 5) << distributed.output;
  // The time of the fall, as the distributed run gives it (a row of its trace may hold it).
  const auto solo_summary = nlohmann::json::parse(summary);
  const auto distributed_summary = nlohmann::json::parse(readFile(distributed.dir / "summary.json"));
  ASSERT_TRUE(solo_summary["fell_at_s"].is_number()) << summary;
  ASSERT_TRUE(distributed_summary["fell_at_s"].is_number()) << distributed_summary.dump(2);
  EXPECT_GT(solo_summary["fell_at_s"].get<double>(), 2.0) << "after the hold";
  EXPECT_NEAR(solo_summary["fell_at_s"].get<double>(), distributed_summary["fell_at_s"].get<double>(), 1e-9);
  // Both traces end at the fall, whatever horizon the distributed clock had granted when the
  // fall reached it: the same bytes.
  const std::string a = readFile(solo.dir / "trace.csv");
  const std::string b = readFile(distributed.dir / "trace.csv");
  ASSERT_GT(lineCount(a), 400u);
  EXPECT_EQ(lineCount(a), lineCount(b));
  EXPECT_TRUE(a == b) << "the solo trace differs from the distributed one";
}

TEST(Solo, TheSummaryHasEveryKeyOfTheDistributedRunsWithTheSameMarks) {
  // ScenarioRun.ASealAndAWheelDriving...: the strips, then wheel 1, leave the pylon's edge (the
  // wheels on the plane, so that the run goes on after it).
  const std::string args = "hold-rough --set start.x_m=3.6 --set start.hold_s=1 --set drive.0.vx_mps=0.1 "
                           "--set duration_s=3.5 --set wall.wheels_on=plane";
  const auto solo = runTool("climbsim-solo", "solo-over-nothing", args);
  ASSERT_EQ(solo.exit_code, 0) << solo.output;
  const auto distributed = runScenario("distributed-over-nothing", args);
  ASSERT_EQ(distributed.exit_code, 0) << distributed.output;
  const auto a = nlohmann::json::parse(readFile(solo.dir / "summary.json"));
  const auto b = nlohmann::json::parse(readFile(distributed.dir / "summary.json"));
  // Every key of the distributed summary but what only several processes have.
  for (const auto& [key, value] : b.items()) {
    if (key == "dropped_samples_by_service") continue;  // per service: solo has one process
    EXPECT_TRUE(a.contains(key)) << key << " is missing in solo's summary:\n" << a.dump(2);
  }
  ASSERT_TRUE(a["wheels_over_nothing"].is_object()) << a.dump(2);
  EXPECT_EQ(a["wheels_over_nothing"], b["wheels_over_nothing"]) << "the same wheel at the same time";
  EXPECT_EQ(a["wheels_over_nothing"]["wheels"], nlohmann::json::array({1}));
  EXPECT_EQ(a["seal_over_nothing"], b["seal_over_nothing"]);
  EXPECT_NE(solo.output.find("wheel 1 stands over nothing at t = "), std::string::npos) << solo.output;
  // On the wall the whole run: null, as the distributed run says.
  const auto on_wall = runTool("climbsim-solo", "solo-on-wall", "hold-rough --set duration_s=0.5");
  ASSERT_EQ(on_wall.exit_code, 0) << on_wall.output;
  const auto c = nlohmann::json::parse(readFile(on_wall.dir / "summary.json"));
  EXPECT_TRUE(c.contains("wheels_over_nothing") && c["wheels_over_nothing"].is_null()) << c.dump(2);
}

TEST(Solo, ASealOverNothingEndsTheRunAsTheDistributedRunDoes) {
  const auto r = runTool("climbsim-solo", "solo-end-on-seal",
                         "hold-rough --set start.x_m=3.6 --set start.hold_s=1 --set drive.0.vx_mps=0.1 "
                         "--set duration_s=3.5 --set end_on.seal_over_nothing=true");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto summary = nlohmann::json::parse(readFile(r.dir / "summary.json"));
  EXPECT_EQ(summary["outcome"], "failed");
  EXPECT_EQ(summary["culprit"], "sealing");
  EXPECT_EQ(summary["exit_code"], 1);
  const std::string reason = summary["reason"].get<std::string>();
  EXPECT_EQ(reason.rfind("participant 'sealing' failed at step ", 0), 0u) << reason;
  const std::string step = reason.substr(37, reason.find(':') - 37);
  EXPECT_EQ(reason.find("step " + step + ": step"), std::string::npos) << "the step once: " << reason;
  EXPECT_NE(reason.find(": SEAL OVER NOTHING at t = "), std::string::npos) << reason;
  EXPECT_NE(reason.find("segment 'outer1' hangs over nothing"), std::string::npos) << reason;
  EXPECT_LT(summary["sim_s"].get<double>(), 3.0) << "the run ended early";
}

TEST(Solo, AnExternalControllerIsRefusedInOneLine) {
  const auto r = runTool("climbsim-solo", "solo-external", "crack-descent --set 'controller={type: external}'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("controller.type = external: a solo run has no DDS"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(r.dir / "trace.csv"));
}

/// The columns of trace.csv whose names start with `prefix`, row by row, as text.
std::vector<std::string> columnsOf(const std::string& trace, const std::string& prefix) {
  std::vector<std::string> rows;
  std::vector<bool> keep;
  std::stringstream lines(trace);
  for (std::string line; std::getline(lines, line);) {
    std::stringstream cells(line);
    std::string picked;
    std::size_t i = 0;
    for (std::string cell; std::getline(cells, cell, ','); ++i) {
      if (keep.size() <= i) keep.push_back(cell.rfind(prefix, 0) == 0);  // the header row
      if (keep[i]) picked += cell + ",";
    }
    rows.push_back(picked);
  }
  return rows;
}

TEST(Solo, ARecordedRunsCommandsPlayedBackGiveItsTraceSoloAndDistributedAndTheirOwnPhysicsElsewhere) {
  // A closed-loop run of crack-descent over the crack (from 4.6 s) with recording.commands; its
  // commands played back by a recorded controller give its trace byte for byte, solo and
  // distributed. At another depth resolution the same commands move the valves exactly as in the
  // recorded run while the chambers follow that resolution's leaks: the controller's decisions
  // held, the physics free.
  const std::string args = "crack-descent --set duration_s=6";
  const auto recorded = runTool("climbsim-solo", "solo-recorded-source", args + " --set recording.commands=true");
  ASSERT_EQ(recorded.exit_code, 0) << recorded.output;
  const std::string replay = args + " --set controller.type=recorded --set controller.commands=" +
                             (recorded.dir / "run.mcap").string();
  const auto solo = runTool("climbsim-solo", "solo-recorded-replay", replay);
  ASSERT_EQ(solo.exit_code, 0) << solo.output;
  const std::string trace = readFile(recorded.dir / "trace.csv");
  EXPECT_TRUE(trace == readFile(solo.dir / "trace.csv")) << "the replay's trace differs from the recorded run's";
  const auto distributed = runScenario("distributed-recorded-replay", replay);
  ASSERT_EQ(distributed.exit_code, 0) << distributed.output;
  EXPECT_TRUE(trace == readFile(distributed.dir / "trace.csv")) << "the distributed replay's trace differs";

  const auto coarse = runTool("climbsim-solo", "solo-recorded-128px", replay + " --set depth_camera.size_px=128");
  ASSERT_EQ(coarse.exit_code, 0) << coarse.output;
  const std::string coarse_trace = readFile(coarse.dir / "trace.csv");
  EXPECT_EQ(columnsOf(coarse_trace, "valve"), columnsOf(trace, "valve"));
  EXPECT_NE(columnsOf(coarse_trace, "leak_area_m2_"), columnsOf(trace, "leak_area_m2_"));
  EXPECT_NE(columnsOf(coarse_trace, "p"), columnsOf(trace, "p"));

  // A recording without commands: one line naming it, exit 2, no trace.
  const auto bare = runTool("climbsim-solo", "solo-recorded-bare", "crack-descent --set duration_s=1");
  ASSERT_EQ(bare.exit_code, 0) << bare.output;
  const auto refused = runTool("climbsim-solo", "solo-recorded-refused",
                               "crack-descent --set duration_s=1 --set controller.type=recorded "
                               "--set controller.commands=" + (bare.dir / "run.mcap").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find((bare.dir / "run.mcap").string() + ": no controller/ValveCommand"), std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(refused.dir / "trace.csv"));
}

TEST(Sweep, SetPointsSoloAndDistributedGiveTheSameVariants) {
  // Two set-points, 4 s each (one value: a fixed key): solo and distributed give the same traces.
  const std::string args = "crack-descent --set duration_s=4 --set controller.downforce_n=900,2200 -j 2";
  const auto solo = runTool("climbsim-sweep", "sweep-solo", args);
  ASSERT_EQ(solo.exit_code, 0) << solo.output;
  const std::string csv = readFile(solo.dir / "sweep.csv");
  EXPECT_EQ(lineCount(csv), 3u) << csv;
  EXPECT_EQ(csv.rfind("variant,duration_s,controller.downforce_n,outcome,fell,min_downforce_n,mean_downforce_n,max_pf_shift_m,"
                      "max_slip_mps,wall_s,dir,slid,slide_m,slide_limit_m,adhesion_failed,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n0,4,900,completed,false,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n1,4,2200,completed,false,"), std::string::npos) << csv;
  for (const char* plot : {"downforce.png", "pf.png"}) {
    EXPECT_GT(fs::exists(solo.dir / plot) ? fs::file_size(solo.dir / plot) : 0u, 1000u) << plot;
  }
  const auto dist = runTool("climbsim-sweep", "sweep-distributed", args + " --distributed");
  ASSERT_EQ(dist.exit_code, 0) << dist.output;
  // --no-mcap: no recording in any variant (nor its whole depth frames), the same traces.
  const auto bare = runTool("climbsim-sweep", "sweep-no-mcap", args + " --no-mcap");
  ASSERT_EQ(bare.exit_code, 0) << bare.output;
  for (const char* variant :
       {"000_duration_s=4__controller.downforce_n=900", "001_duration_s=4__controller.downforce_n=2200"}) {
    EXPECT_TRUE(readFile(solo.dir / variant / "trace.csv") == readFile(dist.dir / variant / "trace.csv")) << variant;
    EXPECT_TRUE(readFile(solo.dir / variant / "trace.csv") == readFile(bare.dir / variant / "trace.csv")) << variant;
    EXPECT_TRUE(fs::exists(solo.dir / variant / "run.mcap")) << variant;
    EXPECT_FALSE(fs::exists(bare.dir / variant / "run.mcap")) << variant;
  }
  const auto refused = runTool("climbsim-sweep", "sweep-no-mcap-distributed", args + " --no-mcap --distributed");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--no-mcap"), std::string::npos) << refused.output;
}

/// The cells of a line of sweep.csv up to its last column (reason, the only one that may be quoted).
std::vector<std::string> cellsBeforeReason(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t at = 0;
  for (std::size_t comma; (comma = line.find(',', at)) != std::string::npos && line[at] != '"'; at = comma + 1) {
    cells.push_back(line.substr(at, comma - at));
  }
  return cells;
}

/// Row `row` (0: the first variant) of sweep.csv as column -> cell, every column but reason.
std::map<std::string, std::string> sweepRow(const std::string& csv, std::size_t row) {
  std::vector<std::string> lines;
  for (std::size_t at = 0, nl; (nl = csv.find('\n', at)) != std::string::npos; at = nl + 1) {
    lines.push_back(csv.substr(at, nl - at));
  }
  std::map<std::string, std::string> out;
  if (row + 1 >= lines.size()) return out;
  const auto header = cellsBeforeReason(lines[0]);
  const auto cells = cellsBeforeReason(lines[row + 1]);
  for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) out[header[i]] = cells[i];
  return out;
}

std::string lastLine(const std::string& text) {
  const auto end = text.find_last_not_of('\n');
  return end == std::string::npos ? "" : text.substr(text.rfind('\n', end) + 1, end - text.rfind('\n', end));
}

TEST(Sweep, ASlideBeyondTheLimitIsToldInSweepCsvAndTheLastLineOfTheRunSoloAndDistributed) {
  // 3 s of crack-descent: 700 N slides 0.72 mm, 1500 N 0.52 mm; a 0.6 mm limit tells them apart.
  const std::string args =
      "crack-descent --set duration_s=3 --set slide_limit_m=0.0006 --set controller.downforce_n=700,1500 -j 2";
  for (const bool distributed : {false, true}) {
    const auto sweep = runTool("climbsim-sweep", distributed ? "sweep-slid-distributed" : "sweep-slid",
                               args + (distributed ? " --distributed" : ""));
    ASSERT_EQ(sweep.exit_code, 0) << sweep.output;
    EXPECT_NE(sweep.output.find("2 of 2 variants finished (0 fell, 1 slid beyond their slide limit, 0 failed)"),
              std::string::npos) << sweep.output;
    const std::string csv = readFile(sweep.dir / "sweep.csv");
    const std::vector<std::string> variants = {"000_duration_s=3__slide_limit_m=0.0006__controller.downforce_n=700",
                                               "001_duration_s=3__slide_limit_m=0.0006__controller.downforce_n=1500"};
    for (std::size_t i = 0; i < variants.size(); ++i) {
      const auto row = sweepRow(csv, i);
      const auto summary = nlohmann::json::parse(readFile(sweep.dir / variants[i] / "summary.json"));
      ASSERT_EQ(row.at("dir"), variants[i]) << csv;
      EXPECT_EQ(row.at("outcome"), "completed") << csv;
      EXPECT_EQ(row.at("fell"), "false") << csv;
      EXPECT_EQ(row.at("slid"), i == 0 ? "true" : "false") << csv;
      EXPECT_EQ(row.at("adhesion_failed"), i == 0 ? "true" : "false") << csv;
      EXPECT_EQ(std::strtod(row.at("slide_m").c_str(), nullptr), summary["slide_m"].get<double>()) << csv;
      EXPECT_EQ(std::strtod(row.at("slide_limit_m").c_str(), nullptr), 0.0006) << csv;
      EXPECT_EQ(row.at("fell_at_s"), "") << csv;
      EXPECT_EQ(row.at("exit_code"), "0") << csv;
      // The run's own last line names the slide (solo's, or the launcher's of the distributed run).
      const std::string last = lastLine(readFile(sweep.dir / (variants[i] + ".log")));
      if (i == 0) {
        EXPECT_NE(last.find("completed, but the robot slid 0.72 mm, beyond the scenario's slide_limit_m of 0.6 mm "
                            "(adhesion failed)"),
                  std::string::npos) << last;
      } else {
        EXPECT_EQ(last.find("the robot slid"), std::string::npos) << last;
      }
    }
  }
}

/// Rows of a trace up to (not including) the first whose t_s is >= t_s.
std::string rowsBefore(const std::string& trace, double t_s) {
  std::size_t at = trace.find('\n') + 1;  // after the header
  while (at < trace.size() && std::strtod(trace.c_str() + at, nullptr) < t_s) at = trace.find('\n', at) + 1;
  return trace.substr(0, at);
}

TEST(Sweep, CrackDepthsGetTheirOwnSceneAndGiveTheSameTraceSoloAndDistributed) {
  // The crack (y = 0.70 m) enters the depth image at about 4 s and reaches the lower outer
  // strip at about 5 s: 7 s see it under the lower chambers.
  const std::string args = "crack-descent --set duration_s=7 --set crack.depth_m=0.002,0.03 -j 2";
  const auto solo = runTool("climbsim-sweep", "sweep-crack-solo", args);
  ASSERT_EQ(solo.exit_code, 0) << solo.output;
  const std::string csv = readFile(solo.dir / "sweep.csv");
  EXPECT_EQ(csv.rfind("variant,duration_s,crack.depth_m,outcome,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n0,7,0.002,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n1,7,0.03,"), std::string::npos) << csv;
  const auto dist = runTool("climbsim-sweep", "sweep-crack-distributed", args + " --distributed");
  ASSERT_EQ(dist.exit_code, 0) << dist.output;
  const std::vector<std::string> variants = {"000_duration_s=7__crack.depth_m=0.002", "001_duration_s=7__crack.depth_m=0.03"};
  std::vector<std::string> traces;
  for (const auto& variant : variants) {
    const fs::path a = solo.dir / variant, b = dist.dir / variant;
    // Each run generated its own pylon into its directory, the same bytes both ways, and its
    // scenario.yaml names that scene.
    const std::string mesh = "scene/meshes/block_c1_r0_crack.ply";
    ASSERT_GT(fs::exists(a / mesh) ? fs::file_size(a / mesh) : 0u, 100000u) << variant;
    EXPECT_TRUE(readFile(a / mesh) == readFile(b / mesh)) << variant;
    EXPECT_NE(readFile(a / "scenario.yaml").find("scene: " + fs::absolute(a / "scene" / "pylon.xml").string()),
              std::string::npos)
        << readFile(a / "scenario.yaml");
    EXPECT_NE(readFile(b / "scenario.yaml").find("scene: " + fs::absolute(b / "scene" / "pylon.xml").string()),
              std::string::npos)
        << readFile(b / "scenario.yaml");
    traces.push_back(readFile(a / "trace.csv"));
    EXPECT_EQ(lineCount(traces.back()), 1401u) << variant;
    EXPECT_TRUE(traces.back() == readFile(b / "trace.csv")) << variant << ": solo and distributed traces differ";
  }
  EXPECT_NE(readFile(solo.dir / variants[0] / "scene/meshes/block_c1_r0_crack.ply"),
            readFile(solo.dir / variants[1] / "scene/meshes/block_c1_r0_crack.ply"));
  // The scenes differ only in the crack: the same trace until the camera sees it, another after.
  EXPECT_TRUE(rowsBefore(traces[0], 3.5) == rowsBefore(traces[1], 3.5));
  EXPECT_GT(rowsBefore(traces[0], 3.5).size(), traces[0].size() / 3);
  EXPECT_FALSE(traces[0] == traces[1]) << "a 2 mm and a 30 mm crack gave the same run";
}

TEST(Sweep, BadInputIsOneLineAndExitTwoBeforeAnyVariant) {
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"crack-descent --set no_such_key=1,2", "no_such_key"},
           {"crack-descent --set duration_s=1,,2", "value 2 of duration_s is empty"},
           {"crack-descent --set duration_s=", "no values for duration_s"},
           {"crack-descent --set duration_s=1,minus", "duration_s"},
           {"crack-descent --set 'controller={type: none},{type: external}'", "controller.type = external"},
           {"crack-descent --set crack.depth_m=0.01,1.5", "crack.depth_m = 1.5: it must be a number in (0, 1]"},
           {"hole-under-chamber --set crack.width_m=0.02",
            "crack = {width_m: 0.02}: only the generated pylon (scene: $BUILD/scenes/pylon.xml) has this crack"},
       }) {
    const auto r = runTool("climbsim-sweep", "sweep-bad", args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(lineCount(r.output), 1u) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(r.dir / "sweep.csv")) << args;
  }
}

TEST(Sweep, CtrlCStopsCleanlyAndKeepsTheFinishedVariants) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "sweep-stopped";
  fs::remove_all(dir);
  const std::string log = dir.string() + ".log";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::freopen(log.c_str(), "w", stderr);
    std::freopen(log.c_str(), "a", stdout);
    const std::string bin = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-sweep";
    // A short first variant, then a long one that is under way at Ctrl-C.
    ::execl(bin.c_str(), bin.c_str(), "crack-descent", "--set", "duration_s=0.5,60", "-j", "1", "--out",
            dir.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const fs::path second = dir / "001_duration_s=60" / "trace.csv";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         !(fs::exists(second) && fs::file_size(second) > 100000)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // polling a file: no event to await
  }
  ASSERT_TRUE(fs::exists(second)) << readFile(log);
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 4) << readFile(log);
  const std::string csv = readFile(dir / "sweep.csv");
  EXPECT_EQ(lineCount(csv), 2u) << "the header and the finished variant\n" << csv;
  EXPECT_NE(csv.find("\n0,0.5,completed,"), std::string::npos) << csv;
  EXPECT_NE(readFile(dir / "001_duration_s=60" / "summary.json").find("\"outcome\": \"stopped\""), std::string::npos);
}

}  // namespace
