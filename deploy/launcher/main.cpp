/// climbsim-compose: the launcher behind `deploy/climbsim up|run|down|ps|logs`. Reads a
/// compose file (deploy/compose.yaml), starts the clock and the services on one DDS
/// domain, and supervises them (docs/design.md#the-shared-simulation-clock,
/// docs/scenario-files.md).

#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/topic_catalog.hpp"
#include "cli.hpp"
#include "commands.hpp"

namespace {
/// The topic catalog as a Markdown table (as docs/design.md#topics-and-qos shows it).
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
  CliValues values;
  const auto app = makeComposeCli(values);
  const auto parsed = [&](const char* command) { return app->get_subcommand(command)->parsed(); };
  return guardedMain(*app, argc, argv, "compose", [&]() -> int {
    if (parsed("topics")) {
      std::cout << topicTable();
      return kExitOk;
    }
    namespace fs = std::filesystem;
    const auto normal = [](const std::string& dir) {
      fs::path p = fs::absolute(dir).lexically_normal();
      return (p.has_filename() ? p : p.parent_path()).string();  // "/a/b/." -> "/a/b", not "/a/b/"
    };
    CommandContext& context = values.context;
    context.root = normal(context.root);
    context.build_dir = normal(context.build_dir);
    context.compose_given = !values.compose_file.empty();
    context.compose_file = values.compose_file.empty() ? context.root + "/deploy/compose.yaml" : values.compose_file;
    if (context.compose_given && !parsed("run") && !parsed("up")) {
      context.compose_file = fs::absolute(context.compose_file).lexically_normal().string();
    }
    if (parsed("up")) {
      return commandUp(context, values.up_options);
    }
    if (parsed("run")) {
      values.up_options.detach = false;
      values.up_options.observers = values.run_viewer;
      return commandUp(context, values.up_options);
    }
    if (parsed("view")) return commandView(context, values.view_options);
    if (parsed("down")) return commandDown(context, values.run_name, values.down_all);
    if (parsed("ps")) return commandPs(context, values.run_name);
    if (parsed("logs")) return commandLogs(context, values.run_name, values.service);
    return kExitConfig;
  });
}
