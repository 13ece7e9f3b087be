/// climbsim-compose: the launcher behind `deploy/climbsim up|run|down|ps|logs`. Reads a
/// compose file (deploy/compose.yaml), starts the clock and the services on one DDS
/// domain, and supervises them (docs/design.md#the-shared-simulation-clock,
/// docs/scenario-files.md).

#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/topic_catalog.hpp"
#include "commands.hpp"

namespace {
/// The topic catalog as a Markdown table (the README's).
std::string topicTable() {
  std::string out = "| topic | type | producer | rate | QoS profile |\n|---|---|---|---|---|\n";
  for (const auto& t : climbsim::kTopicCatalog) {
    out += std::string("| `") + t.name + "` | `climbsim::" + t.type + "` | " + t.producer + " | " + t.rate + " | `" +
           t.qos + "` |\n";
  }
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::launcher;
  CLI::App app{"climbsim-compose: start, supervise and stop a climbsim composition"};
  CommandContext context;
  std::string compose_file;
  UpOptions up_options;
  std::string service;
  std::string run_name;
  bool down_all = false;
  app.add_option("--root", context.root, "the climbsim repository")->required();
  app.add_option("--build", context.build_dir, "the build directory (programs in bin/, runs in run/)")->required();
  app.require_subcommand(1);
  const auto add_file_option = [&](CLI::App* command) {
    command->add_option("-f,--file", compose_file, "compose file (default: <root>/deploy/compose.yaml)");
  };
  const auto add_run_options = [&](CLI::App* command) {
    command->add_option("--name", up_options.name,
                        "run name (run directory <build>/run/NAME; default: the scenario's name, made unique)");
    command->add_option("--rtf", up_options.rtf, "real-time factor of the clock (0: as fast as possible)");
    command->add_option("--domain", up_options.domain, "DDS domain id 0..232 (default: the compose file's, or a free one)");
    command->add_flag("--secure", up_options.secure,
                      "DDS Security (as `security: on`): certificates, permissions, encryption (see README)");
    command->add_flag("--check", up_options.check,
                      "validate the compose file, the scenario and its robot and scene; run nothing");
  };
  auto* up = app.add_subcommand("up", "start the clock and every service; in the foreground until the run ends");
  add_file_option(up);
  add_run_options(up);
  up->add_flag("-d,--detach", up_options.detach, "supervise in the background and print the run directory");
  up->add_option("--scenario", up_options.scenario, "scenario file or name in deploy/scenarios (default: the compose file's)");
  up->add_option("--set", up_options.overrides, "override a scenario key: --set duration_s=5 (repeatable)");
  up->add_option("--window-steps", up_options.window_steps, "the clock's horizon window W in steps (1 = one grant per step)");
  auto* run = app.add_subcommand("run", "start everything, run to the end; exit 0 only if the run completed");
  add_file_option(run);
  add_run_options(run);
  run->add_option("SCENARIO", up_options.scenario, "scenario file or name in deploy/scenarios (default: the compose file's)");
  run->add_option("--out", up_options.out_dir, "run directory: trace, summary, plots, logs (DIR/logs)");
  run->add_option("--set", up_options.overrides, "override a scenario key: --set duration_s=5 (repeatable)");
  run->add_option("--window-steps", up_options.window_steps, "the clock's horizon window W in steps (1 = one grant per step)");
  bool run_viewer = false;
  run->add_flag("--viewer", run_viewer, "also start the compose file's observers (the viewer: open its address)");
  ViewOptions view_options;
  auto* view = app.add_subcommand("view", "replay a finished run directory in the browser (climbsim-viewer)");
  view->add_option("RUN_DIR", view_options.run_dir, "the run directory (trace.csv, scenario.yaml)")->required();
  view->add_option("--port", view_options.port, "TCP port of the page")->check(CLI::Range(1, 65535));
  view->add_option("--bind", view_options.bind, "IPv4 address to listen on (0.0.0.0: every interface)");
  const auto add_filter_option = [&](CLI::App* command) {
    command->add_option("-f,--file", compose_file, "only runs of this compose file");
  };
  auto* down = app.add_subcommand("down", "stop a run (clock first, then signals): RUN, or the only one running");
  add_filter_option(down);
  down->add_option("RUN", run_name, "the run's name (see 'ps')");
  down->add_flag("--all", down_all, "stop every running run");
  auto* ps = app.add_subcommand("ps", "list the runs; with RUN: its processes (name, host, pid, state)");
  add_filter_option(ps);
  ps->add_option("RUN", run_name, "the run's name");
  auto* logs = app.add_subcommand("logs", "print the logs of a run: RUN, or the only one running, or the last one");
  add_filter_option(logs);
  logs->add_option("RUN", run_name, "the run's name (or a service of the only run)");
  logs->add_option("SERVICE", service, "only this service (or process)");
  auto* topics = app.add_subcommand("topics", "print the table of every DDS topic: name, type, producer, rate, QoS");
  return guardedMain(app, argc, argv, "compose", [&]() -> int {
    if (topics->parsed()) {
      std::cout << topicTable();
      return kExitOk;
    }
    namespace fs = std::filesystem;
    const auto normal = [](const std::string& dir) {
      fs::path p = fs::absolute(dir).lexically_normal();
      return (p.has_filename() ? p : p.parent_path()).string();  // "/a/b/." -> "/a/b", not "/a/b/"
    };
    context.root = normal(context.root);
    context.build_dir = normal(context.build_dir);
    context.compose_given = !compose_file.empty();
    context.compose_file = compose_file.empty() ? context.root + "/deploy/compose.yaml" : compose_file;
    if (context.compose_given && !run->parsed() && !up->parsed()) {
      context.compose_file = fs::absolute(context.compose_file).lexically_normal().string();
    }
    if (up->parsed()) {
      return commandUp(context, up_options);
    }
    if (run->parsed()) {
      up_options.detach = false;
      up_options.observers = run_viewer;
      return commandUp(context, up_options);
    }
    if (view->parsed()) return commandView(context, view_options);
    if (down->parsed()) return commandDown(context, run_name, down_all);
    if (ps->parsed()) return commandPs(context, run_name);
    if (logs->parsed()) return commandLogs(context, run_name, service);
    return kExitConfig;
  });
}
