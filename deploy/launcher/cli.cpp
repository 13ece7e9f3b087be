#include "cli.hpp"

namespace climbsim::launcher {

std::unique_ptr<CLI::App> makeComposeCli(CliValues& values) {
  auto app = std::make_unique<CLI::App>("climbsim-compose: start, supervise and stop a climbsim composition");
  app->add_option("--root", values.context.root, "the climbsim repository")->required();
  app->add_option("--build", values.context.build_dir, "the build directory (programs in bin/, runs in run/)")
      ->required();
  app->require_subcommand(1);
  UpOptions& up_options = values.up_options;
  const auto add_file_option = [&](CLI::App* command) {
    command->add_option("-f,--file", values.compose_file, "compose file (default: <root>/deploy/compose.yaml)");
  };
  const auto add_run_options = [&](CLI::App* command) {
    command->add_option("--name", up_options.name,
                        "run name (run directory <build>/run/NAME; default: the scenario's name, made unique)");
    command->add_option("--rtf", up_options.rtf, "real-time factor of the clock (0: as fast as possible)");
    command->add_option("--domain", up_options.domain, "DDS domain id 0..232 (default: the compose file's, or a free one)");
    command->add_flag("--secure", up_options.secure,
                      "DDS Security (as `security: on`): certificates, permissions, encryption "
                      "(see docs/deployment.md#dds-security)");
    command->add_flag("--check", up_options.check,
                      "validate the compose file, the scenario and its robot and scene; run nothing");
    command->add_option("--set", up_options.overrides, "override a scenario key: --set duration_s=5 (repeatable)");
    command->add_option("--window-steps", up_options.window_steps,
                        "the clock's horizon window W in steps (1 = one grant per step)");
  };
  auto* up = app->add_subcommand("up", "start the clock and every service; in the foreground until the run ends");
  add_file_option(up);
  add_run_options(up);
  up->add_flag("-d,--detach", up_options.detach, "supervise in the background and print the run directory");
  up->add_option("--scenario", up_options.scenario, "scenario file or name in deploy/scenarios (default: the compose file's)");
  auto* run = app->add_subcommand("run", "start everything, run to the end; exit 0 only if the run completed");
  add_file_option(run);
  add_run_options(run);
  run->add_option("SCENARIO", up_options.scenario, "scenario file or name in deploy/scenarios (default: the compose file's)");
  run->add_option("--out", up_options.out_dir, "run directory: trace, summary, plots, logs (DIR/logs)");
  run->add_flag("--viewer", values.run_viewer, "also start the compose file's observers (the viewer: open its address)");
  auto* view = app->add_subcommand("view", "replay a finished run directory in the browser (climbsim-viewer)");
  view->add_option("RUN_DIR", values.view_options.run_dir, "the run directory (trace.csv, scenario.yaml)")->required();
  view->add_option("--port", values.view_options.port, "TCP port of the page")->check(CLI::Range(1, 65535));
  view->add_option("--bind", values.view_options.bind, "IPv4 address to listen on (0.0.0.0: every interface)");
  view->add_option("--snapshot", values.view_options.snapshot,
                   "write a PNG picture of the page (3D view drawn) instead of serving it, then stop");
  view->add_option("--at", values.view_options.at_s, "time of the snapshot [s] (default: the run's end)");
  const auto add_filter_option = [&](CLI::App* command) {
    command->add_option("-f,--file", values.compose_file, "only runs of this compose file");
  };
  auto* down = app->add_subcommand("down", "stop a run (clock first, then signals): RUN, or the only one running");
  add_filter_option(down);
  down->add_option("RUN", values.run_name, "the run's name (see 'ps')");
  down->add_flag("--all", values.down_all, "stop every running run");
  auto* ps = app->add_subcommand("ps", "list the runs; with RUN: its processes (name, host, pid, state)");
  add_filter_option(ps);
  ps->add_option("RUN", values.run_name, "the run's name");
  auto* logs = app->add_subcommand("logs", "print the logs of a run: RUN, or the only one running, or the last one");
  add_filter_option(logs);
  logs->add_option("RUN", values.run_name, "the run's name (or a service of the only run)");
  logs->add_option("SERVICE", values.service, "only this service (or process)");
  app->add_subcommand("topics", "print the table of every DDS topic: name, type, producer, rate, QoS");
  return app;
}

}  // namespace climbsim::launcher
