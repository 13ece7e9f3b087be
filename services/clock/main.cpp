/// climbsim-clock: the shared lockstep simulation clock
/// (docs/design.md#the-shared-simulation-clock).

#include <csignal>
#include <random>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/main_guard.hpp"
#include "climbsim/names.hpp"
#include "configure.hpp"
#include "node/clock_node.hpp"
#include "node/robot_shape_idl.hpp"

namespace {
std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-clock: the lockstep simulation clock"};
  DdsSettings dds;
  std::string roster;
  double step_ms = 5.0;
  std::optional<double> duration_s;
  std::optional<std::uint64_t> steps;
  double rtf = 0.0;
  double start_timeout_s = 30.0;
  double step_timeout_s = 10.0;
  bool start_paused = false;
  std::uint32_t window_steps = climbsim::clock::kDefaultWindowSteps;
  std::optional<std::uint64_t> run_id;
  std::optional<double> max_pause_s;
  std::string control_from;
  std::string robot_file;
  app.add_option("--roster", roster, "required participants, comma-separated (e.g. scene,sealing,thermo)")->required();
  app.add_option("--step-ms", step_ms, "length of one clock step [ms]");
  auto* duration_opt = app.add_option("--duration-s", duration_s, "simulated time to run [s]");
  app.add_option("--steps", steps, "number of steps to run")->excludes(duration_opt);
  app.add_option("--rtf", rtf, "real-time factor: 0 = as fast as possible, 1 = wall-clock paced");
  app.add_option("--start-timeout-s", start_timeout_s, "fail if the roster is not complete after this long [s]");
  app.add_option("--step-timeout-s", step_timeout_s, "watchdog: fail if a step takes longer than this [s]");
  app.add_option("--window-steps", window_steps,
                 "W: the horizon runs at most W steps ahead of the slowest participant (1 = one grant per step)");
  app.add_flag("--start-paused", start_paused, "hold before step 0 until resumed or single-stepped");
  app.add_option("--run-id", run_id, "identifier of this run (default: random)");
  app.add_option("--max-pause-s", max_pause_s, "a pause nobody resumes within this ends the run (default: none)");
  auto* control_opt = app.add_option("--control-from", control_from,
                 "DDS participants that may send ClockControl: name[@addr[/addr...]],... (default: anybody)");
  app.add_option("--robot", robot_file,
                 "the run's robot (a robot file, or a shipped robot's name): RunStart carries it to every participant");
  dds.addOptions(app);
  return guardedMain(app, argc, argv, "clock", [&]() -> int {
    clock::ClockParams params;
    params.roster = parseNameList("--roster", roster);
    const clock::ClockTiming timing = clock::clockTiming(step_ms, duration_s, steps);
    params.dt_ns = timing.dt_ns;
    params.end_step = timing.end_step;
    params.realtime_factor = rtf;
    params.start_timeout = clock::durationOption("--start-timeout-s", start_timeout_s);
    params.step_timeout = clock::durationOption("--step-timeout-s", step_timeout_s);
    params.start_paused = start_paused;
    if (control_opt->count() > 0) {
      params.control_senders = clock::parseControlSenders("--control-from", control_from);
    }
    if (max_pause_s) {
      params.max_pause = clock::durationOption("--max-pause-s", *max_pause_s);
    }
    params.window_steps = window_steps;
    params.run_id = run_id ? *run_id : std::random_device{}() | (static_cast<std::uint64_t>(std::random_device{}()) << 32);
    dds.resolve();
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    clock::ClockNode node(dds, params, robot_file.empty() ? climbsim::RobotShape{} : clock::robotShapeFromFile(robot_file));
    return node.run(g_stop);
  });
}
