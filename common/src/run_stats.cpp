#include "climbsim/run_stats.hpp"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>

namespace climbsim {

namespace {
std::mutex& statsMutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<std::string, double>& counters() {
  static std::map<std::string, double> values;
  return values;
}
}  // namespace

void statsAdd(const std::string& key, double value) {
  std::lock_guard<std::mutex> lock(statsMutex());
  counters()[key] += value;
}

StatsTimer::~StatsTimer() {
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::lock_guard<std::mutex> lock(statsMutex());
  counters()[key_] += s;
  counters()[std::string(key_) + "_n"] += 1.0;
}

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

StatsCpuTimer::StatsCpuTimer(const char* key) : key_(key), start_s_(threadCpuSeconds()) {}

StatsCpuTimer::~StatsCpuTimer() {
  const double s = threadCpuSeconds() - start_s_;
  std::lock_guard<std::mutex> lock(statsMutex());
  counters()[key_] += s;
  counters()[std::string(key_) + "_n"] += 1.0;
}

void writeStatsIfAsked(const std::string& name) {
  const char* dir = std::getenv("CLIMBSIM_STATS_DIR");
  if (dir == nullptr || *dir == '\0') return;
  nlohmann::json json;
  {
    std::lock_guard<std::mutex> lock(statsMutex());
    for (const auto& [key, value] : counters()) json[key] = value;
  }
  const std::string path = std::string(dir) + "/" + name + ".json";
  std::ofstream out(path, std::ios::trunc);
  out << json.dump(2) << "\n";
  if (!out) spdlog::warn("cannot write the run statistics to {}", path);
}

void logDroppedSamples(std::uint64_t count, const std::string& detail) {
  if (count > 0) {
    spdlog::warn("dropped_samples={} ({})", count, detail);
  } else {
    spdlog::info("dropped_samples=0 ({})", detail);
  }
}

}  // namespace climbsim
