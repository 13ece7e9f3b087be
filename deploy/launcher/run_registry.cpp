#include "run_registry.hpp"

#include <algorithm>
#include <filesystem>

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"

namespace climbsim::launcher {

namespace {
namespace fs = std::filesystem;

/// Room for "-999" after a default name.
constexpr std::size_t kMaxBaseLength = kMaxNameLength - 4;
constexpr int kMaxSuffix = 999;

bool isNameChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == '.';
}

std::string describeRuns(const std::vector<RunEntry>& runs, bool only_running) {
  std::string out;
  for (const auto& run : runs) {
    if (only_running && !run.running) continue;
    out += (out.empty() ? "" : ", ") + run.name;
  }
  return out.empty() ? "none" : out;
}
}  // namespace

void validateRunName(const std::string& name) {
  try {
    validateName("--name", name);
  } catch (const ConfigError&) {
    throw ConfigError("--name " + name.substr(0, 64) + (name.size() > 64 ? "..." : "") +
                      ": a run name is 1.." + std::to_string(kMaxNameLength) +
                      " letters, digits, '_', '-' and '.'");
  }
  if (name.find_first_not_of('.') == std::string::npos) {
    throw ConfigError("--name " + name + ": a run name cannot be only dots (it names a directory)");
  }
}

std::string baseRunName(const std::string& base) {
  std::string out;
  for (const char c : base) {
    out += isNameChar(c) ? c : '-';
  }
  if (out.size() > kMaxBaseLength) out.resize(kMaxBaseLength);
  if (out.find_first_not_of(".-") == std::string::npos) out = "run";
  return out;
}

std::optional<ClaimedRun> claimRun(const std::string& build_dir, const std::string& base, bool explicit_name) {
  const int last = explicit_name ? 1 : kMaxSuffix;
  for (int i = 1; i <= last; ++i) {
    const std::string name = i == 1 ? base : base + "-" + std::to_string(i);
    RunPaths paths(build_dir, name);
    fs::create_directories(paths.dir);
    auto lock = FileLock::tryLock(paths.lock_file);
    if (lock) {
      return ClaimedRun{name, paths, std::move(*lock)};
    }
  }
  return std::nullopt;
}

std::vector<RunEntry> listRuns(const std::string& build_dir) {
  std::vector<RunEntry> runs;
  const fs::path root = fs::path(build_dir) / "run";
  std::error_code error;
  if (!fs::is_directory(root, error)) return runs;
  for (const auto& entry : fs::directory_iterator(root, error)) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    RunEntry run{name, RunPaths(build_dir, name), false, std::nullopt};
    if (!fs::exists(run.paths.state_file) && !fs::exists(run.paths.lock_file)) continue;
    run.running = FileLock::isHeld(run.paths.lock_file);
    try {
      run.state = readRunState(run.paths.state_file);
    } catch (const std::exception&) {
    }
    runs.push_back(std::move(run));
  }
  std::sort(runs.begin(), runs.end(), [](const RunEntry& a, const RunEntry& b) {
    if (a.running != b.running) return a.running;
    const std::string sa = a.state ? a.state->started_at : "";
    const std::string sb = b.state ? b.state->started_at : "";
    if (sa != sb) return sa > sb;
    return a.name < b.name;
  });
  return runs;
}

std::optional<RunEntry> selectRun(const std::string& build_dir, const std::string& name,
                                  const std::string& compose_file, bool allow_finished) {
  std::vector<RunEntry> runs = listRuns(build_dir);
  if (!compose_file.empty()) {
    runs.erase(std::remove_if(runs.begin(), runs.end(),
                              [&](const RunEntry& r) { return !r.state || r.state->compose_file != compose_file; }),
               runs.end());
  }
  if (!name.empty()) {
    for (auto& run : runs) {
      if (run.name == name) return run;
    }
    throw ConfigError("no run named '" + name + "' (runs: " + describeRuns(runs, false) + ")");
  }
  const auto running = std::count_if(runs.begin(), runs.end(), [](const RunEntry& r) { return r.running; });
  if (running > 1) {
    throw ConfigError(std::to_string(running) + " runs are running (" + describeRuns(runs, true) +
                      "): name one");
  }
  if (running == 1) return runs.front();
  if (allow_finished && !runs.empty()) return runs.front();
  return std::nullopt;
}

}  // namespace climbsim::launcher
