#include "run_state.hpp"

#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace climbsim::launcher {

RunPaths::RunPaths(const std::string& build_dir, const std::string& run_name)
    : dir((std::filesystem::path(build_dir) / "run" / run_name).lexically_normal().string()),
      logs_dir(dir + "/logs"),
      state_file(dir + "/state.json"),
      lock_file(dir + "/supervisor.lock"),
      supervisor_log(dir + "/supervisor.log") {}

std::string RunPaths::logFile(const std::string& process) const { return logs_dir + "/" + process + ".log"; }

std::string runStateToJson(const RunState& state) {
  nlohmann::json processes = nlohmann::json::array();
  for (const auto& p : state.processes) {
    nlohmann::json entry = {{"name", p.name}, {"pid", p.pid}};
    entry["exit_code"] = p.exit_code ? nlohmann::json(*p.exit_code) : nlohmann::json(nullptr);
    entry["host"] = p.host;
    entry["cpu_s"] = p.cpu_s ? nlohmann::json(*p.cpu_s) : nlohmann::json(nullptr);
    entry["ctx_switches"] = p.ctx_switches ? nlohmann::json(*p.ctx_switches) : nlohmann::json(nullptr);
    processes.push_back(entry);
  }
  nlohmann::json json = {
      {"compose_name", state.compose_name}, {"compose_file", state.compose_file},
      {"run_dir", state.run_dir},           {"supervisor_pid", state.supervisor_pid},
      {"detached", state.detached},         {"domain_id", state.domain_id},
      {"started_at", state.started_at},     {"processes", processes},
  };
  json["name"] = state.name;
  json["scenario"] = state.scenario;
  json["out_dir"] = state.out_dir;
  json["rtf"] = state.rtf;
  json["viewer_url"] = state.viewer_url;
  json["exit_code"] = state.exit_code ? nlohmann::json(*state.exit_code) : nlohmann::json(nullptr);
  return json.dump(2) + "\n";
}

RunState runStateFromJson(const std::string& text, const std::string& source) {
  try {
    const auto json = nlohmann::json::parse(text);
    RunState state;
    state.compose_name = json.at("compose_name").get<std::string>();
    state.compose_file = json.at("compose_file").get<std::string>();
    state.run_dir = json.at("run_dir").get<std::string>();
    state.supervisor_pid = json.at("supervisor_pid").get<pid_t>();
    state.detached = json.at("detached").get<bool>();
    state.domain_id = json.at("domain_id").get<int>();
    state.started_at = json.at("started_at").get<std::string>();
    state.name = json.value("name", state.compose_name);
    state.scenario = json.value("scenario", std::string());
    state.out_dir = json.value("out_dir", std::string());
    state.rtf = json.value("rtf", 0.0);
    state.viewer_url = json.value("viewer_url", std::string());
    for (const auto& entry : json.at("processes")) {
      ProcessState p;
      p.name = entry.at("name").get<std::string>();
      p.pid = entry.at("pid").get<pid_t>();
      if (!entry.at("exit_code").is_null()) {
        p.exit_code = entry.at("exit_code").get<int>();
      }
      p.host = entry.value("host", std::string("local"));
      if (entry.contains("ctx_switches") && !entry.at("ctx_switches").is_null()) {
        p.ctx_switches = entry.at("ctx_switches").get<std::uint64_t>();
      }
      if (entry.contains("cpu_s") && !entry.at("cpu_s").is_null()) {
        p.cpu_s = entry.at("cpu_s").get<double>();
      }
      state.processes.push_back(p);
    }
    if (!json.at("exit_code").is_null()) {
      state.exit_code = json.at("exit_code").get<int>();
    }
    return state;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(source + ": malformed run state: " + e.what());
  }
}

void writeRunState(const std::string& path, const RunState& state) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << runStateToJson(state);
    if (!out.flush()) {
      throw std::runtime_error("cannot write '" + temporary + "'");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    throw std::runtime_error("cannot rename '" + temporary + "' to '" + path + "': " + error.message());
  }
}

std::optional<RunState> readRunState(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return runStateFromJson(text.str(), path);
}

std::string localTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  ::localtime_r(&now, &local);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%S", &local);
  return buffer;
}

}  // namespace climbsim::launcher
