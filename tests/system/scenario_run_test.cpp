// Whole scenario runs through the launcher, as a user starts them: `climbsim-compose run`
// with every service of deploy/compose.yaml as a separate process on real Fast DDS.

#include <gtest/gtest.h>

#include "launcher_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <cmath>
#include <future>
#include <sstream>
#include <string>
#include <fcntl.h>
#include <signal.h>
#include <thread>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <chrono>
#include <thread>

namespace {

using namespace climbsim::system_test;

/// The downforce column of trace.csv.
std::vector<double> downforce(const fs::path& trace) {
  std::vector<double> out;
  std::istringstream lines(readFile(trace));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) out.push_back(std::strtod(line.c_str() + line.find(',') + 1, nullptr));
  return out;
}

/// Row `row` of trace.csv by column name.
std::map<std::string, double> traceRow(const fs::path& trace, std::size_t row) {
  std::istringstream lines(readFile(trace));
  std::string header, line;
  std::getline(lines, header);
  for (std::size_t k = 0; k <= row; ++k) std::getline(lines, line);
  std::map<std::string, double> out;
  std::istringstream names(header), cells(line);
  for (std::string name, cell; std::getline(names, name, ',') && std::getline(cells, cell, ',');) {
    out[name] = std::strtod(cell.c_str(), nullptr);
  }
  return out;
}

/// A number of summary.json, NaN if it is absent or not a number.
double summaryNumber(const std::string& summary, const std::string& key) {
  const auto at = summary.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  const char* value = summary.c_str() + at + key.size() + 4;
  char* end = nullptr;
  const double v = std::strtod(value, &end);
  return end == value ? std::nan("") : v;
}

/// The lines of `text` that contain `needle`.
std::vector<std::string> linesWith(const std::string& text, const std::string& needle) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(needle) != std::string::npos) out.push_back(line);
  }
  return out;
}

TEST(ScenarioRun, CrackDescentCompletesOnTheWallAndRepeatsBitForBit) {
  // 8 s: held for 2 s, then 0.3 m down the wall towards the crack.
  const auto first = runScenario("system-crack-descent-1", "crack-descent --set duration_s=8");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string summary = readFile(first.dir / "summary.json");
  EXPECT_NE(summary.find("\"completed\": true"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"fell\": false"), std::string::npos) << summary;
  EXPECT_TRUE(fs::exists(first.dir / "scenario.yaml"));
  // The launcher plots every run; the scenario asks for pictures at 1, 5 and 7 s (of 8).
  for (const char* plot : {"downforce.png", "pressures.png", "valves.png", "wheel_loads.png", "ring_5s.png"}) {
    EXPECT_GT(fs::exists(first.dir / "plots" / plot) ? fs::file_size(first.dir / "plots" / plot) : 0u, 1000u) << plot;
  }
  EXPECT_TRUE(fs::exists(first.dir / "pictures" / "sealing_gaps_7s.png"));
  const auto f = downforce(first.dir / "trace.csv");
  ASSERT_EQ(f.size(), 1600u);
  // Once the vacuum is built the reference controller keeps the robot well above what it
  // needs to hold (m g / mu = 631 N) on rough concrete.
  for (std::size_t k = 400; k < f.size(); ++k) ASSERT_GT(f[k], 1000.0) << "row " << k;
  // Every row is data, row 0 too: the producers' states before step 0.
  const std::string trace = readFile(first.dir / "trace.csv");
  EXPECT_EQ(trace.find("nan"), std::string::npos) << "a NaN cell in trace.csv";
  const auto row0 = traceRow(first.dir / "trace.csv", 0);
  EXPECT_EQ(row0.at("t_s"), 0.0);
  EXPECT_EQ(row0.at("downforce_n"), 0.0) << "every chamber at ambient pulls nothing";
  for (const char* p : {"p1_pa", "p4_pa", "p7_pa", "pr_pa"}) EXPECT_EQ(row0.at(p), 100000.0) << p;  // cromsci.yaml
  for (const char* v : {"valve1", "valve7"}) EXPECT_EQ(row0.at(v), 0.0) << v;
  EXPECT_EQ(row0.at("x_m"), 1.0) << "the scenario's start pose";
  EXPECT_EQ(row0.at("y_m"), 1.2);
  // Resting on the scene's rough surface the body tilts by a few mrad; its yaw is the start
  // pose's to within 10 µrad.
  EXPECT_NEAR(row0.at("yaw_rad"), -3.14159265358979323846 / 2, 1e-5);
  EXPECT_EQ(row0.at("wheel1_slip_mps"), 0.0) << "at rest";
  // The downforce statistics start at the release (2 s), not at the 0 N of the evacuation.
  EXPECT_EQ(summaryNumber(summary, "downforce_from_s"), 2.0) << summary;
  EXPECT_GT(summaryNumber(summary, "min_downforce_n"), 631.0) << summary;  // m g / mu
  EXPECT_GT(summaryNumber(summary, "mean_downforce_n"), summaryNumber(summary, "min_downforce_n")) << summary;
  EXPECT_LT(summaryNumber(summary, "max_pf_shift_m"), 0.4) << "P_F within the robot: " << summary;
  EXPECT_NE(summary.find("\"seal_over_nothing\": null"), std::string::npos) << "on the wall: " << summary;
  EXPECT_EQ(summaryNumber(summary, "downforce_setpoint_n"), 2200.0) << "the reference controller's: " << summary;

  const auto second = runScenario("system-crack-descent-2", "crack-descent --set duration_s=8");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(readFile(first.dir / "trace.csv") == readFile(second.dir / "trace.csv"))
      << "the same scenario gave a different trace";
}

TEST(ScenarioRun, ASealAndAWheelDrivingPastTheEdgeOfTheSceneAreNamedAtTheStepAndMarkedInTheSummary) {
  // The pylon's blocks end at x = 4 m. The robot starts on the wall at x = 3.6 m (its outer
  // strip reaches 3.96 m, wheel 1 3.86 m), is released at 1 s and drives right at 0.1 m/s: the
  // strips there, then wheel 1, leave the scene. Not silently, and each at the step it happens.
  // With the wheels on the wall plane (a wheel over nothing is still pressed on) the run goes on;
  // on the scene's surface, the default, wheel 1 drops off the edge and the robot falls (below).
  const std::string args =
      "hold-rough --set start.x_m=3.6 --set start.hold_s=1 --set drive.0.vx_mps=0.1 --set duration_s=3.5";
  const auto r = runScenario("system-seal-over-nothing", args + " --set wall.wheels_on=plane");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string marker = "hangs over nothing";
  const auto first = r.output.find(marker);
  ASSERT_NE(first, std::string::npos) << r.output;
  EXPECT_NE(r.output.find("segment 'outer1'"), std::string::npos) << "the strip at the edge: " << r.output;
  // Once per segment: no segment is named twice however many frames see it.
  std::map<std::string, int> named;
  for (auto at = first; at != std::string::npos; at = r.output.find(marker, at + 1)) {
    const auto seg = r.output.rfind("segment '", at);
    ++named[r.output.substr(seg, r.output.find('\'', seg + 9) - seg)];
  }
  for (const auto& [segment, count] : named) EXPECT_EQ(count, 1) << segment;
  const std::string summary = readFile(r.dir / "summary.json");
  EXPECT_NE(summary.find("\"seal_over_nothing\": {"), std::string::npos) << summary;
  const double seal_at = summaryNumber(summary.substr(summary.find("\"seal_over_nothing\"")), "first_at_s");
  EXPECT_GT(seal_at, 1.0) << "the strips were on the wall until the robot moved: " << summary;
  // Wheel 1 (along R's x, 0.26 m from the centre) leaves when the centre passes 3.74 m: after
  // the strip (0.36 m), and only wheel 1 in 3.5 s.
  const std::string wheel_line = "drive: wheel 1 stands over nothing at t = ";
  const auto wheel_at = r.output.find(wheel_line);
  ASSERT_NE(wheel_at, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(wheel_line, wheel_at + 1), std::string::npos) << "named once";
  EXPECT_EQ(r.output.find("drive: wheel 2 stands over nothing"), std::string::npos) << r.output;
  const double wheel_t = std::strtod(r.output.c_str() + wheel_at + wheel_line.size(), nullptr);
  EXPECT_GT(wheel_t, seal_at);
  ASSERT_NE(summary.find("\"wheels_over_nothing\": {"), std::string::npos) << summary;
  const std::string wheels = summary.substr(summary.find("\"wheels_over_nothing\""));
  EXPECT_NEAR(summaryNumber(wheels, "first_at_s"), wheel_t, 1e-9) << summary;
  // The trace's pose at that time has wheel 1's contact point at the edge (within a 5 mm cell).
  const auto row = traceRow(r.dir / "trace.csv", static_cast<std::size_t>(std::llround(wheel_t / 0.005)));
  EXPECT_NEAR(row.at("x_m") + 0.26 * std::cos(row.at("yaw_rad")), 4.0, 0.006) << "wheel 1 at the edge";

  // On the surface: wheel 1 is named over nothing, loses its ground, and the robot falls off
  // the edge after it (exit code 5), not before.
  const auto off = runScenario("system-wheel-off-the-edge", args);
  EXPECT_EQ(off.exit_code, 5) << off.output;
  const auto off_wheel = off.output.find(wheel_line);
  ASSERT_NE(off_wheel, std::string::npos) << off.output;
  const auto fell = off.output.find("FELL at t = ");
  ASSERT_NE(fell, std::string::npos) << off.output;
  EXPECT_GT(std::strtod(off.output.c_str() + fell + std::string("FELL at t = ").size(), nullptr),
            std::strtod(off.output.c_str() + off_wheel + wheel_line.size(), nullptr));
}

TEST(ScenarioRun, ASealOverNothingEndsTheRunWhenTheScenarioSaysSo) {
  // As above, with end_on.seal_over_nothing: the run fails at the step the first strip (outer1)
  // hangs over nothing, naming it and the time, and the trace keeps the rows up to there.
  const auto r = runScenario("system-end-on-seal",
                             "hold-rough --set start.x_m=3.6 --set start.hold_s=1 --set drive.0.vx_mps=0.1 "
                             "--set duration_s=3.5 --set end_on.seal_over_nothing=true");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const std::string summary = readFile(r.dir / "summary.json");
  EXPECT_NE(summary.find("\"outcome\": \"failed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"culprit\": \"sealing\""), std::string::npos) << summary;
  const auto at = summary.find("SEAL OVER NOTHING at t = ");
  ASSERT_NE(at, std::string::npos) << summary;
  EXPECT_NE(summary.find("segment 'outer1' hangs over nothing"), std::string::npos) << summary;
  // The step once (the clock's "at step N"), then the sealing's own reason.
  EXPECT_NE(summary.find("\"reason\": \"participant 'sealing' failed at step "), std::string::npos) << summary;
  const auto step_at = summary.find("failed at step ") + 15;
  const std::string step = summary.substr(step_at, summary.find(':', step_at) - step_at);
  EXPECT_EQ(summary.find("step " + step + ": step " + step), std::string::npos) << summary;
  EXPECT_NE(summary.find("failed at step " + step + ": SEAL OVER NOTHING at t = "), std::string::npos) << summary;
  const double t = std::strtod(summary.c_str() + at + 25, nullptr);
  EXPECT_GT(t, 1.0) << "the strips were on the wall until the robot moved";
  EXPECT_LT(summaryNumber(summary, "sim_s"), 3.0) << "the run ended early: " << summary;
  EXPECT_GE(summaryNumber(summary, "sim_s"), t - 0.1) << summary;
}

TEST(ScenarioRun, AStartPoseAlreadyOffTheSceneIsRefusedBeforeAnythingStarts) {
  // Held at x = 3.8 m the robot would hang 0.2 m past the pylon's edge from the start.
  const auto r = runScenario("system-start-off-scene", "hold-rough --set start.x_m=3.8 --set duration_s=0.5");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("hold-rough.yaml (--set start.x_m=3.8): start.x_m = 3.8: the robot would start off the "
                          "scene: wheel 1 and strips outer1 (100 %)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("starting '"), std::string::npos) << "nothing started: " << r.output;
  EXPECT_FALSE(fs::exists(r.dir / "trace.csv"));
}

// Every shipped scenario at W = 1 and the default W: Solo.EveryShippedScenarioGivesTheSameTrace-
// SoloAndDistributed (solo_test.cpp) runs each both ways and against the solo run.

TEST(ScenarioRun, AWindowDeeperThanTheQueuesStopsBeforeStepZeroWithOneLine) {
  const auto r = runScenario("system-window-too-deep", "crack-descent --set duration_s=3 --window-steps 100");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.find("starting"), std::string::npos) << "nothing may start\n" << r.output;
  EXPECT_NE(r.output.find("window_steps (--window-steps) = 100: above 32"), std::string::npos) << r.output;
  const std::string trace = fs::exists(r.dir / "trace.csv") ? readFile(r.dir / "trace.csv") : std::string();
  EXPECT_LE(std::count(trace.begin(), trace.end(), '\n'), 1) << "no step may run: at most the header";
}

TEST(ScenarioRun, AFallEndsTheRunWithItsOwnOutcomeExitCodeAndLine) {
  // No controller: no vacuum; the robot slides off once the hold ends at 2 s.
  const auto fell = runScenario("system-fall", "crack-descent --set duration_s=6 --set 'controller={type: none}'");
  EXPECT_EQ(fell.exit_code, 5) << fell.output;
  EXPECT_NE(fell.output.find("FELL at t = 2."), std::string::npos) << fell.output;
  const std::string summary = readFile(fell.dir / "summary.json");
  EXPECT_NE(summary.find("\"outcome\": \"fell\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"completed\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"exit_code\": 5"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"culprit\": \"drive\""), std::string::npos) << summary;
  const auto f = downforce(fell.dir / "trace.csv");
  EXPECT_GT(f.size(), 400u) << "the trace keeps the hold and the fall";
  EXPECT_LT(f.size(), 600u) << "and ends soon after it";

  const auto on = runScenario("system-fall-goes-on",
                              "crack-descent --set duration_s=3 --set 'controller={type: none}' --set end_on.fall=false");
  EXPECT_EQ(on.exit_code, 0) << on.output;
  const std::string on_summary = readFile(on.dir / "summary.json");
  EXPECT_NE(on_summary.find("\"outcome\": \"completed\""), std::string::npos) << on_summary;
  EXPECT_NE(on_summary.find("\"fell\": true"), std::string::npos) << on_summary;
}

TEST(ScenarioRun, AStoppedRunSaysStoppedAndExitsFour) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "system-stopped";
  fs::remove_all(dir);
  const std::string log = dir.string() + ".log";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    const std::string bin = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose";
    const std::string out = dir.string();
    ::execl(bin.c_str(), bin.c_str(), "--root", CLIMBSIM_ROOT, "--build", CLIMBSIM_BUILD_DIR, "run", "crack-descent",
            "--set", "duration_s=60", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until rows are being written (the run is under way), then Ctrl-C the launcher.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::size_t rows = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string trace = fs::exists(dir / "trace.csv") ? readFile(dir / "trace.csv") : std::string();
    rows = static_cast<std::size_t>(std::count(trace.begin(), trace.end(), '\n'));
    if (rows > 200) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // polling a file: no event to await
  }
  ASSERT_GT(rows, 200u) << readFile(log);
  ::kill(pid, SIGINT);  // what Ctrl-C sends
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 4) << readFile(log);
  const std::string summary = readFile(dir / "summary.json");
  EXPECT_NE(summary.find("\"outcome\": \"stopped\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"completed\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"exit_code\": 4"), std::string::npos) << summary;
}

TEST(ScenarioRun, TheReadmesTwoStepCheckRunSaysARealTimeFactorWithItsDigits) {
  // Two steps: the recorder's wall time is mostly starting and stopping, a factor well below
  // 0.1, which must keep its digits, not print as "0.0x real time".
  const auto r = runScenario("system-two-steps", "crack-descent --set duration_s=0.01");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find(" 0.0x real time"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("(0.00x real time)"), std::string::npos) << r.output;
  std::vector<std::string> lines;
  for (const auto& line : linesWith(r.output, " real time")) {
    if (line.find("x real time") != std::string::npos || line.find("n/a real time") != std::string::npos) {
      lines.push_back(line);
    }
  }
  ASSERT_FALSE(lines.empty()) << r.output;
  for (const auto& line : lines) {
    const auto at = line.rfind(' ', line.find(" real time") - 1) + 1;
    std::string figure = line.substr(at, line.find(" real time") - at);
    if (!figure.empty() && figure.front() == '(') figure.erase(0, 1);  // the clock's "(4.1x real time)"
    EXPECT_TRUE(figure == "n/a" || (figure.back() == 'x' && std::strtod(figure.c_str(), nullptr) > 0.0)) << line;
  }
}

TEST(ScenarioRun, ABadScenarioStopsBeforeAnythingStartsWithOneLine) {
  const auto r = runScenario("system-bad-scenario", "crack-descent --set controller.type=magic");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("crack-descent.yaml (--set controller.type=magic): controller.type = magic"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(r.dir / "trace.csv"));
}

TEST(ScenarioRun, ARobotFileThatDoesNotLoadStopsBeforeAnythingStarts) {
  const fs::path robot = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "bad-robot.yaml";
  fs::create_directories(robot.parent_path());
  std::string text = readFile(fs::path(CLIMBSIM_ROOT) / "deploy" / "robots" / "cromsci.yaml");
  const auto mass = text.find("mass_kg:");
  ASSERT_NE(mass, std::string::npos);
  text.replace(mass, 8, "mass_kg: -45 #");
  std::ofstream(robot) << text;
  const auto r = runScenario("system-bad-robot", "crack-descent --set robot=" + robot.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(robot.string() + ":"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mass_kg = -45"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("starting '"), std::string::npos) << "services were started:\n" << r.output;
  EXPECT_FALSE(fs::exists(r.dir / "trace.csv"));
}

TEST(ScenarioRun, TwoRunsSideBySideFromOneCheckoutGetTheirOwnNamesAndDomains) {
  // Two launchers at once, neither given a name: crack-descent and crack-descent-2, each on a
  // DDS domain of its own, and (deterministic) the same trace.
  const std::string args = "crack-descent --set duration_s=1.5 --set start.hold_s=0.5";
  auto a = std::async(std::launch::async, [&] { return runScenario("system-side-a", args); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto b = std::async(std::launch::async, [&] { return runScenario("system-side-b", args); });
  const RunResult ra = a.get();
  const RunResult rb = b.get();
  ASSERT_EQ(ra.exit_code, 0) << ra.output;
  ASSERT_EQ(rb.exit_code, 0) << rb.output;
  const auto started_a = linesWith(ra.output, "starting '");
  const auto started_b = linesWith(rb.output, "starting '");
  ASSERT_EQ(started_a.size(), 1u) << ra.output;
  ASSERT_EQ(started_b.size(), 1u) << rb.output;
  // "starting 'NAME' on DDS domain N (...)"
  const auto nameAndDomain = [](const std::string& line) {
    const auto at = line.find("starting '");
    return line.substr(at, line.find(" (", at) - at);
  };
  EXPECT_NE(nameAndDomain(started_a[0]), nameAndDomain(started_b[0]));
  EXPECT_NE(started_a[0].find("starting 'crack-descent"), std::string::npos) << started_a[0];
  const std::string domain_a = started_a[0].substr(started_a[0].find("domain "));
  const std::string domain_b = started_b[0].substr(started_b[0].find("domain "));
  EXPECT_NE(domain_a.substr(0, domain_a.find(' ', 7)), domain_b.substr(0, domain_b.find(' ', 7)));
  // Whichever started second while the first ran got the -2 name.
  const bool one_is_2 = started_a[0].find("'crack-descent-2'") != std::string::npos ||
                        started_b[0].find("'crack-descent-2'") != std::string::npos;
  EXPECT_TRUE(one_is_2) << started_a[0] << "\n" << started_b[0];
  EXPECT_TRUE(readFile(ra.dir / "trace.csv") == readFile(rb.dir / "trace.csv"));

  // `ps` lists both runs; `ps NAME` and `logs NAME SERVICE` pick one.
  const std::string compose = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose --root " + CLIMBSIM_ROOT +
                              " --build " + CLIMBSIM_BUILD_DIR;
  const fs::path ps_log = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "system-side-ps.log";
  ASSERT_EQ(std::system((compose + " ps > " + ps_log.string() + " 2>&1").c_str()), 0);
  const std::string ps = readFile(ps_log);
  EXPECT_NE(ps.find("crack-descent "), std::string::npos) << ps;
  EXPECT_NE(ps.find("crack-descent-2 "), std::string::npos) << ps;
  EXPECT_NE(ps.find("exited 0"), std::string::npos) << ps;
  ASSERT_EQ(std::system((compose + " logs crack-descent-2 recorder > " + ps_log.string() + " 2>&1").c_str()), 0);
  EXPECT_NE(readFile(ps_log).find("run completed"), std::string::npos) << readFile(ps_log);
}

/// The response (status line, headers and body) of `GET /` at url "http://HOST:PORT/", "" if
/// nothing answers.
std::string httpGet(const std::string& url) {
  const auto host_at = url.find("//") + 2;
  const auto colon = url.find(':', host_at);
  const std::string host = url.substr(host_at, colon - host_at);
  const int port = std::atoi(url.c_str() + colon + 1);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1) return "";
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return "";
  std::string response;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0) {
    const std::string request = "GET / HTTP/1.0\r\nHost: " + host + "\r\n\r\n";
    if (::write(fd, request.data(), request.size()) == static_cast<ssize_t>(request.size())) {
      char buffer[4096];
      for (ssize_t got; (got = ::read(fd, buffer, sizeof buffer)) > 0;) response.append(buffer, static_cast<std::size_t>(got));
    }
  }
  ::close(fd);
  return response;
}

/// Starts `climbsim-compose run <args...> --out <runs>/<tag>` with its output in <runs>/<tag>.log.
pid_t startLauncher(const std::string& tag, std::vector<std::string> args) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  const std::string log = dir.string() + ".log";
  const std::string bin = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose";
  std::vector<std::string> argv = {bin, "--root", CLIMBSIM_ROOT, "--build", CLIMBSIM_BUILD_DIR, "run"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--out", dir.string()});
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> c_argv;
    for (auto& a : argv) c_argv.push_back(a.data());
    c_argv.push_back(nullptr);
    ::execv(bin.c_str(), c_argv.data());
    ::_exit(127);
  }
  return pid;
}

TEST(ScenarioRun, TwoRunsAtOnceEachGetAViewerWhoseAddressServesThePage) {
  // Both viewers on deploy/compose.yaml's default port 8765: the second (or both, if another
  // program holds 8765) takes the next free port, and the launcher says which.
  const std::vector<std::string> args = {"crack-descent", "--viewer", "--set", "duration_s=60"};
  const pid_t a = startLauncher("system-viewer-a", args);
  const pid_t b = startLauncher("system-viewer-b", args);
  ASSERT_GT(a, 0);
  ASSERT_GT(b, 0);
  const std::string marker = "is at http://";
  const auto addressIn = [&](const std::string& tag) -> std::string {
    const std::string log = readFile(fs::path(CLIMBSIM_TEST_RUNS_DIR) / (tag + ".log"));
    const auto at = log.find(marker);
    if (at == std::string::npos) return "";
    const auto begin = at + marker.size() - 7;
    return log.substr(begin, log.find_first_of(" \n", begin) - begin);
  };
  std::string url_a, url_b;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(180);
  while (std::chrono::steady_clock::now() < deadline && (url_a.empty() || url_b.empty())) {
    url_a = addressIn("system-viewer-a");
    url_b = addressIn("system-viewer-b");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // polling a file: no event to await
  }
  const std::string page_a = url_a.empty() ? "" : httpGet(url_a);
  const std::string page_b = url_b.empty() ? "" : httpGet(url_b);
  // `ps` of the run shows the address too (what a detached `up` did not print).
  const fs::path ps_log = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "system-viewer-ps.log";
  const std::string compose = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose --root " + CLIMBSIM_ROOT +
                              " --build " + CLIMBSIM_BUILD_DIR;
  EXPECT_EQ(std::system((compose + " ps > " + ps_log.string() + " 2>&1").c_str()), 0);
  const std::string ps_list = readFile(ps_log);  // the runs, then each running run's processes
  ::kill(a, SIGINT);
  ::kill(b, SIGINT);
  int status_a = 0, status_b = 0;
  ::waitpid(a, &status_a, 0);
  ::waitpid(b, &status_b, 0);
  const std::string log_a = readFile(fs::path(CLIMBSIM_TEST_RUNS_DIR) / "system-viewer-a.log");
  const std::string log_b = readFile(fs::path(CLIMBSIM_TEST_RUNS_DIR) / "system-viewer-b.log");
  ASSERT_FALSE(url_a.empty()) << log_a;
  ASSERT_FALSE(url_b.empty()) << log_b;
  EXPECT_NE(url_a, url_b);
  EXPECT_NE(ps_list.find(", viewer " + url_a + ")"), std::string::npos) << ps_list;
  EXPECT_NE(ps_list.find(", viewer " + url_b + ")"), std::string::npos) << ps_list;
  for (const auto& [url, page] : {std::pair{url_a, page_a}, std::pair{url_b, page_b}}) {
    EXPECT_EQ(page.rfind("HTTP/1.", 0), 0u) << url << "\n" << page.substr(0, 200);
    EXPECT_EQ(page.find(" 200 "), 8u) << url << "\n" << page.substr(0, 200);
    EXPECT_NE(page.find("<title>climbsim viewer</title>"), std::string::npos) << url;
  }
  for (const std::string* log : {&log_a, &log_b}) {
    EXPECT_EQ(log->find("observer 'viewer' exited with code"), std::string::npos) << *log;
  }
  EXPECT_EQ(WIFEXITED(status_a) ? WEXITSTATUS(status_a) : -1, 4) << log_a;
  EXPECT_EQ(WIFEXITED(status_b) ? WEXITSTATUS(status_b) : -1, 4) << log_b;
}

TEST(ScenarioRun, SwitchingTheControllerOffFromTheCommandLineIgnoresTheSetPointWithOneWarning) {
  // crack-descent.yaml's reference controller has downforce_n: 2200; without a controller the
  // robot falls once the hold ends (2 s).
  const auto r = runScenario("system-controller-none", "crack-descent --set duration_s=4 --set controller.type=none");
  EXPECT_EQ(r.exit_code, 5) << r.output;
  const auto warned = linesWith(r.output, "is ignored");
  ASSERT_EQ(warned.size(), 1u) << r.output;
  EXPECT_NE(warned[0].find("crack-descent.yaml:12: controller.downforce_n = 2200 is ignored: --set controller.type=none "
                           "takes no set-point"),
            std::string::npos)
      << warned[0];
  EXPECT_EQ(readFile(r.dir / "scenario.yaml").find("downforce_n"), std::string::npos) << "the run's copy has none";
  EXPECT_NE(readFile(r.dir / "summary.json").find("\"outcome\": \"fell\""), std::string::npos);
}

TEST(ScenarioRun, CheckValidatesWithoutRunningAndReportsEveryProblemInLineOrder) {
  // `run --check` (docs/scenario-files.md#checking-a-scenario): the scenario, its robot, scene and
  // compose file; nothing runs.
  const auto ok = runScenario("system-check-ok", "crack-descent --check");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("ok: "), std::string::npos) << ok.output;
  EXPECT_EQ(ok.output.find("starting '"), std::string::npos) << ok.output;
  EXPECT_FALSE(fs::exists(ok.dir / "trace.csv"));

  const fs::path bad = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "three-typos.yaml";
  std::string text = readFile(fs::path(CLIMBSIM_ROOT) / "deploy" / "scenarios" / "crack-descent.yaml");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("robot: cromsci", "robot: " + (fs::path(CLIMBSIM_ROOT) / "deploy/robots/cromsci.yaml").string());
  replace("duration_s:", "duraton_s: 3\nduration_s:");
  replace("step_ms: 5", "step_ms: -5");
  replace("seed:", "seed: 1\nsede:");
  std::ofstream(bad) << text;
  const auto r = runScenario("system-check-bad", bad.string() + " --check");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto errors = linesWith(r.output, bad.string() + ":");
  ASSERT_EQ(errors.size(), 3u) << r.output;  // duraton_s (unknown), step_ms (negative), sede (unknown)
  // A scene without the element the scene service moves the robot with: refused before the start,
  // naming the compose file's scene service (next to the generated scene: its meshes resolve).
  const fs::path scene = fs::path(CLIMBSIM_BUILD_DIR) / "scenes" / "test-no-pose.xml";
  std::string xml = readFile(fs::path(CLIMBSIM_BUILD_DIR) / "scenes" / "pylon.xml");
  const auto pose = xml.find("name=\"robot_pose\"");
  ASSERT_NE(pose, std::string::npos);
  xml.replace(pose, 17, "name=\"robot_pos\"");
  std::ofstream(scene) << xml;
  const auto no_pose = runScenario("system-check-no-pose", "crack-descent --check --set scene=" + scene.string());
  fs::remove(scene);
  EXPECT_EQ(no_pose.exit_code, 2) << no_pose.output;
  EXPECT_NE(no_pose.output.find("no 3d Pose element \"robot_pose\""), std::string::npos) << no_pose.output;
  EXPECT_NE(no_pose.output.find("compose.yaml"), std::string::npos) << no_pose.output;
  int last_line = 0;
  for (const auto& e : errors) {
    const auto at = e.find(bad.string() + ":") + bad.string().size() + 1;
    const int line = std::atoi(e.c_str() + at);
    EXPECT_GE(line, last_line) << r.output;
    last_line = line;
  }
}

}  // namespace

namespace {

TEST(ScenarioRun, CheckChecksTheSceneGeneratedForACrack) {
  // A crack wider and deeper than the camera reaches, under the start pose: --check generates
  // the pylon the run would use (into a scratch directory) and refuses the start on it, in one
  // line, exit 2. The same start on the shipped pylon (its 10 mm crack) passes.
  const std::string start = "crack-descent --check --set start.y_m=0.7";
  const auto shipped = runScenario("system-check-crack-shipped", start);
  EXPECT_EQ(shipped.exit_code, 0) << shipped.output;
  const auto cracked =
      runScenario("system-check-crack-wide", start + " --set crack.depth_m=0.5 --set crack.width_m=0.4");
  EXPECT_EQ(cracked.exit_code, 2) << cracked.output;
  const auto errors = linesWith(cracked.output, " error: ");
  ASSERT_EQ(errors.size(), 1u) << cracked.output;
  EXPECT_NE(errors[0].find("crack-descent.yaml:"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("start = {x_m: 1, y_m: 0.7"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("generated with crack {depth_m: 0.5, width_m: 0.4}"), std::string::npos) << errors[0];
  EXPECT_EQ(cracked.output.find("starting '"), std::string::npos) << cracked.output;
  // The scratch directory is gone with the check.
  const auto into = cracked.output.find(" into /");
  ASSERT_NE(into, std::string::npos) << cracked.output;
  const std::string scratch = cracked.output.substr(into + 6, cracked.output.find('\n', into) - into - 6);
  EXPECT_FALSE(fs::exists(scratch)) << scratch;
}

}  // namespace
