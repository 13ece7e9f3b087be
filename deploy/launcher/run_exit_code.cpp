#include "run_exit_code.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/run_summary/run_summary.hpp"

namespace climbsim::launcher {

int runExitCode(const std::vector<ProcessEnd>& processes) {
  if (processes.empty()) return kExitFailed;
  const bool config = std::any_of(processes.begin(), processes.end(),
                                  [](const ProcessEnd& p) { return p.exit_code == kExitConfig; });
  if (config) return kExitConfig;
  const int clock_code = processes.front().exit_code.value_or(kExitFailed);
  if (clock_code != kExitOk) return clock_code;
  const bool any_failed = std::any_of(processes.begin(), processes.end(),
                                      [](const ProcessEnd& p) { return p.exit_code.value_or(kExitFailed) != kExitOk; });
  return any_failed ? kExitFailed : kExitOk;
}

std::optional<std::string> configCulprit(const std::vector<ProcessEnd>& processes) {
  for (std::size_t i = 1; i < processes.size(); ++i) {
    if (processes[i].exit_code == kExitConfig) return processes[i].name;
  }
  return std::nullopt;
}

std::vector<std::size_t> blameOrder(const std::vector<int>& exit_codes) {
  std::vector<std::size_t> order(exit_codes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) { return exit_codes[i] > 128; });
  return order;
}

bool startAgain(const std::vector<ProcessEnd>& processes, bool secured, int starts) {
  return secured && starts < kMaxStarts &&
         std::any_of(processes.begin(), processes.end(),
                     [](const ProcessEnd& end) { return end.exit_code == kExitRetryStart; });
}

bool agreeOnConfigError(const std::string& out_dir, int exit_code, const std::string& culprit) {
  if (exit_code != kExitConfig) return false;
  return run_summary::editSummary(out_dir, [&](nlohmann::json& summary) {
    if (summary.value("exit_code", -1) == kExitConfig) return false;
    summary["exit_code"] = kExitConfig;
    summary["outcome"] = "failed";
    summary["completed"] = false;
    if (!summary.contains("culprit") || !summary["culprit"].is_string() || summary["culprit"].get<std::string>().empty()) {
      summary["culprit"] = culprit;
    }
    summary["configuration_error"] = true;
    return true;
  });
}

}  // namespace climbsim::launcher
