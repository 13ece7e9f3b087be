#include "replay_server.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "climbsim/errors.hpp"
#include "climbsim/grid_record.hpp"
#include "recorded_depth_grids.hpp"
#include "replay_run.hpp"

namespace climbsim::viewer {
namespace {
namespace fs = std::filesystem;

std::string readBinary(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

HttpResponse json(const nlohmann::json& value) { return {200, "application/json", value.dump()}; }
}  // namespace

int serveReplay(const ViewerOptions& options, const std::atomic<bool>& quit) {
  const fs::path dir = fs::absolute(options.replay_dir);
  if (!fs::is_directory(dir)) throw ConfigError(options.replay_dir + ": no such run directory");
  const std::string trace_file = (dir / "trace.csv").string();
  if (!fs::exists(trace_file)) throw ConfigError(trace_file + ": no trace.csv: not a run directory");
  const std::string scenario_file = (dir / "scenario.yaml").string();
  if (!fs::exists(scenario_file)) throw ConfigError(scenario_file + ": missing: not a run directory");
  const std::string hello = helloText("replay", scenario_file);
  const nlohmann::json trace_columns = loadTraceColumns(trace_file);
  const std::string trace = trace_columns.dump();
  const nlohmann::json pictures = listSealingPictures(dir.string());
  // The recording when there is one (a cut-short or corrupt one is refused: one line, exit 2);
  // the depth grids from viewer/depth_grids.jsonl, or else from the recording.
  const fs::path recording = dir / "run.mcap";
  std::vector<std::pair<double, std::string>> grids = loadGridRecords(gridRecordPath(dir.string()));
  if (fs::exists(recording)) {
    auto recorded = recordedDepthGrids(recording.string());
    if (grids.empty()) grids = std::move(recorded);
  }
  WebServer server(options.web);
  server.handle("/api/", [&](const std::string& path, const std::string& query) -> HttpResponse {
    if (path == "/api/hello") return {200, "application/json", hello};
    if (path == "/api/trace") return {200, "application/json", trace};
    if (path == "/api/pictures") return json(pictures);
    if (path == "/api/depth") {  // ?t=<seconds>: the wall under the robot then, if recorded
      const auto at = query.find("t=");
      const double t_s = at == std::string::npos ? 0.0 : std::strtod(query.c_str() + at + 2, nullptr);
      const std::string& grid = gridAt(grids, t_s);
      return grid.empty() ? HttpResponse{200, "application/json", "null"} : HttpResponse{200, "application/json", grid};
    }
    return {404, "text/plain", "no such data: " + path + "\n"};
  });
  server.handle("/run/", [&](const std::string& path, const std::string&) -> HttpResponse {
    for (const auto& picture : pictures) {  // only what the listing offers: no path escapes
      if (path == "/run/" + picture["file"].get<std::string>()) {
        return {200, "image/png", readBinary(dir / picture["file"].get<std::string>())};
      }
    }
    return {404, "text/plain", "not found: " + path + "\n"};
  });
  spdlog::info("replay of {} ({} rows, {} depth grids, {} sealing pictures) at {}", dir.string(),
               trace_columns["values"].empty() ? 0 : trace_columns["values"][0].size(), grids.size(), pictures.size(),
               server.url());
  while (!quit) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  return kExitOk;
}

}  // namespace climbsim::viewer
