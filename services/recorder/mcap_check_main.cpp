/// climbsim-mcap-check FILE: what a recording (RUN_DIR/run.mcap) holds, read from its start
/// record by record (recording/mcap_check.hpp): for a closed file a line with its chunks,
/// messages and last time, then one line per channel (topic, schema, messages, last log time),
/// exit 0. A file that is cut short (a killed recorder) or corrupt, or no MCAP file, is one line
/// on stderr saying where it ends and what reads before that, and exit code 2.
/// docs/recordings.md#checking-a-recording.

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/recording/mcap_check.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-mcap-check: messages per channel of an MCAP recording, and whether it was closed"};
  std::string path;
  app.add_option("FILE", path, "an MCAP file, e.g. RUN_DIR/run.mcap")->required();
  return guardedMain(app, argc, argv, "mcap-check", [&]() -> int {
    const recording::McapCheck check = recording::checkMcap(path);
    const double last_s = static_cast<double>(check.lastLogTimeNs()) * 1e-9;
    if (!check.closed) {
      std::string counts;
      for (const auto& [topic, c] : check.channels) {
        counts += (counts.empty() ? "" : ", ") + topic + " " + std::to_string(c.messages);
      }
      std::fprintf(stderr, "climbsim mcap-check: %s: %s; it reads up to there: %llu messages%s%s%s\n", path.c_str(),
                   check.problem.c_str(), static_cast<unsigned long long>(check.messages()),
                   check.messages() > 0 ? fmt::format(" up to t = {:.3f} s", last_s).c_str() : "",
                   counts.empty() ? "" : " (", counts.empty() ? "" : (counts + ")").c_str());
      return kExitConfig;
    }
    std::printf("%s: closed, %llu bytes, %llu chunks, %llu metadata records, %llu messages up to t = %.3f s\n",
                path.c_str(), static_cast<unsigned long long>(check.file_bytes),
                static_cast<unsigned long long>(check.chunks), static_cast<unsigned long long>(check.metadata),
                static_cast<unsigned long long>(check.messages()), last_s);
    std::printf("%-24s %-28s %10s %12s\n", "topic", "schema", "messages", "last t [s]");
    for (const auto& [topic, c] : check.channels) {
      const std::string last =
          c.messages > 0 ? fmt::format("{:.3f}", static_cast<double>(c.last_log_time_ns) * 1e-9) : "-";
      std::printf("%-24s %-28s %10llu %12s\n", topic.c_str(), c.schema.c_str(),
                  static_cast<unsigned long long>(c.messages), last.c_str());
    }
    return kExitOk;
  });
}
