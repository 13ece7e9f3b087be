/// climbsim-compose: the launcher behind `deploy/climbsim up|run|down|ps|logs`. Reads a
/// compose file (deploy/compose.yaml), starts the clock and the services on one DDS
/// domain, and supervises them (DESIGN.md §2, §6).

#include <filesystem>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::launcher;
  CLI::App app{"climbsim-compose: start, supervise and stop a climbsim composition"};
  CommandContext context;
  std::string compose_file;
  UpOptions up_options;
  std::string service;
  app.add_option("--root", context.root, "the climbsim repository")->required();
  app.add_option("--build", context.build_dir, "the build directory (programs in bin/, runs in run/)")->required();
  app.require_subcommand(1);
  const auto add_file_option = [&](CLI::App* command) {
    command->add_option("-f,--file", compose_file, "compose file (default: <root>/deploy/compose.yaml)");
  };
  auto* up = app.add_subcommand("up", "start the clock and every service; in the foreground until the run ends");
  add_file_option(up);
  up->add_flag("-d,--detach", up_options.detach, "supervise in the background and print the run directory");
  up->add_option("--scenario", up_options.scenario, "scenario file or name in deploy/scenarios (default: the compose file's)");
  up->add_option("--set", up_options.overrides, "override a scenario key: --set duration_s=5 (repeatable)");
  auto* run = app.add_subcommand("run", "start everything, run to the end; exit 0 only if the run completed");
  add_file_option(run);
  run->add_option("SCENARIO", up_options.scenario, "scenario file or name in deploy/scenarios (default: the compose file's)");
  run->add_option("--out", up_options.out_dir, "run directory: trace, summary, plots, logs (DIR/logs)");
  run->add_option("--set", up_options.overrides, "override a scenario key: --set duration_s=5 (repeatable)");
  bool run_viewer = false;
  run->add_flag("--viewer", run_viewer, "also start the compose file's observers (the viewer: open its address)");
  ViewOptions view_options;
  auto* view = app.add_subcommand("view", "replay a finished run directory in the browser (climbsim-viewer)");
  view->add_option("RUN_DIR", view_options.run_dir, "the run directory (trace.csv, scenario.yaml)")->required();
  view->add_option("--port", view_options.port, "TCP port of the page")->check(CLI::Range(1, 65535));
  view->add_option("--bind", view_options.bind, "IPv4 address to listen on (0.0.0.0: every interface)");
  auto* down = app.add_subcommand("down", "stop the running composition (clock first, then signals)");
  add_file_option(down);
  auto* ps = app.add_subcommand("ps", "list the processes of the composition: name, pid, state");
  add_file_option(ps);
  auto* logs = app.add_subcommand("logs", "print the logs of the running (or last) run");
  add_file_option(logs);
  logs->add_option("SERVICE", service, "only this service (or process)");
  return guardedMain(app, argc, argv, "compose", [&]() -> int {
    namespace fs = std::filesystem;
    context.root = fs::absolute(context.root).lexically_normal().string();
    context.build_dir = fs::absolute(context.build_dir).lexically_normal().string();
    context.compose_file = compose_file.empty() ? context.root + "/deploy/compose.yaml" : compose_file;
    if (up->parsed()) {
      return commandUp(context, up_options);
    }
    if (run->parsed()) {
      up_options.detach = false;
      up_options.observers = run_viewer;
      return commandUp(context, up_options);
    }
    if (view->parsed()) return commandView(context, view_options);
    if (down->parsed()) return commandDown(context);
    if (ps->parsed()) return commandPs(context);
    if (logs->parsed()) return commandLogs(context, service);
    return kExitConfig;
  });
}
