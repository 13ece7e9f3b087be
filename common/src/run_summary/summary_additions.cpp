#include "climbsim/run_summary/summary_additions.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "climbsim/run_summary/run_summary.hpp"

namespace climbsim::run_summary {

std::optional<WheelOverNothing> wheelOverNothingIn(std::string_view line) {
  constexpr std::string_view kWheel = "wheel ";
  constexpr std::string_view kMiddle = " stands over nothing at t = ";
  const auto middle = line.find(kMiddle);
  if (middle == std::string_view::npos) return std::nullopt;
  const auto wheel_at = line.rfind(kWheel, middle);
  if (wheel_at == std::string_view::npos) return std::nullopt;
  const std::string number(line.substr(wheel_at + kWheel.size(), middle - wheel_at - kWheel.size()));
  const std::string time(line.substr(middle + kMiddle.size(), 32));
  char* end = nullptr;
  const long wheel = std::strtol(number.c_str(), &end, 10);
  if (number.empty() || *end != '\0' || wheel < 1 || wheel > 64) return std::nullopt;
  const double at_s = std::strtod(time.c_str(), &end);
  if (end == time.c_str() || !std::isfinite(at_s)) return std::nullopt;
  return WheelOverNothing{static_cast<int>(wheel), at_s};
}

nlohmann::json wheelsOverNothingJson(const std::vector<WheelOverNothing>& wheels) {
  if (wheels.empty()) return nullptr;
  double first = wheels.front().at_s;
  nlohmann::json numbers = nlohmann::json::array();
  for (const auto& w : wheels) {
    first = std::min(first, w.at_s);
    if (std::find(numbers.begin(), numbers.end(), w.wheel) == numbers.end()) numbers.push_back(w.wheel);
  }
  return {{"first_at_s", first}, {"wheels", numbers}};
}

void addWheelsOverNothing(const std::string& out_dir, const std::vector<WheelOverNothing>& wheels) {
  editSummary(out_dir, [&](nlohmann::json& summary) {
    summary["wheels_over_nothing"] = wheelsOverNothingJson(wheels);
    return true;
  });
}

std::optional<std::uint64_t> droppedSamplesIn(std::string_view line) {
  constexpr std::string_view kToken = "dropped_samples=";
  const auto at = line.find(kToken);
  if (at == std::string_view::npos) return std::nullopt;
  std::size_t end = at + kToken.size();
  std::uint64_t n = 0;
  bool any = false;
  while (end < line.size() && line[end] >= '0' && line[end] <= '9' && n < (UINT64_MAX - 9) / 10) {
    n = n * 10 + static_cast<std::uint64_t>(line[end] - '0');
    ++end;
    any = true;
  }
  return any ? std::optional<std::uint64_t>(n) : std::nullopt;
}

void addDroppedSamples(const std::string& out_dir, const std::map<std::string, std::uint64_t>& by_service) {
  std::uint64_t total = 0;
  const bool written = editSummary(out_dir, [&](nlohmann::json& summary) {
    std::uint64_t own = summary.contains("dropped_samples") && summary["dropped_samples"].is_number_unsigned()
                            ? summary["dropped_samples"].get<std::uint64_t>()
                            : 0;
    if (summary.contains("dropped_samples_by_service")) own = summary["dropped_samples_by_service"].value("recorder", own);
    nlohmann::json each = nlohmann::json::object();
    each["recorder"] = own;
    total = own;
    for (const auto& [service, n] : by_service) {
      if (service == "recorder") continue;
      each[service] = n;
      total += n;
    }
    summary["dropped_samples"] = total;
    summary["dropped_samples_by_service"] = each;
    return true;
  });
  if (written && total > 0) {
    spdlog::warn("the services dropped {} samples in all (summary.json dropped_samples_by_service)", total);
  }
}

bool fillFailureReason(const std::string& out_dir, const std::string& clock_reason) {
  if (clock_reason.empty()) return false;
  return editSummary(out_dir, [&](nlohmann::json& summary) {
    const auto empty = [&](const char* key) {
      return !summary.contains(key) || !summary[key].is_string() || summary[key].get<std::string>().empty();
    };
    if (summary.value("outcome", "") != "failed" || !empty("reason")) return false;
    summary["reason"] = clock_reason;
    constexpr std::string_view kParticipant = "participant '";
    if (empty("culprit") && clock_reason.rfind(kParticipant, 0) == 0) {
      const auto end = clock_reason.find('\'', kParticipant.size());
      if (end != std::string::npos) summary["culprit"] = clock_reason.substr(kParticipant.size(), end - kParticipant.size());
    }
    return true;
  });
}

}  // namespace climbsim::run_summary
