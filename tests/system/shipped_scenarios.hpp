#pragma once
// The scenarios of deploy/scenarios, found on disk: a test that covers "every shipped scenario"
// covers a new one without an edit.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace climbsim::system_test {

/// One shipped scenario and how long a test runs it.
struct ShippedScenario {
  std::string name;      ///< file stem, as `climbsim run NAME` takes it
  double check_s;        ///< simulated seconds of a check run
  double step_ms = 5.0;  ///< the file's step_ms (5 when left out)
};

/// Every deploy/scenarios/*.yaml, sorted by name. A check run covers the 2 s hold, the release
/// and the first metres: 5 s, except where a scenario costs much more per simulated second
/// (crack-descent-hires: 1024 px images and the sealing at 100 Hz, about 8x the work per
/// second: 3 s still release it).
inline std::vector<ShippedScenario> shippedScenarios() {
  std::vector<ShippedScenario> out;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(CLIMBSIM_ROOT) / "deploy" / "scenarios")) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().stem().string();
    ShippedScenario s{name, name.find("hires") != std::string::npos ? 3.0 : 5.0};
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("step_ms:", 0) == 0) s.step_ms = std::stod(line.substr(8));
    }
    out.push_back(s);
  }
  std::sort(out.begin(), out.end(), [](const ShippedScenario& a, const ShippedScenario& b) { return a.name < b.name; });
  return out;
}

/// Rows of a check run's trace.csv: row 0 (the initial states) and one per step but the last.
inline std::size_t checkRows(const ShippedScenario& s) {
  return static_cast<std::size_t>(s.check_s * 1000.0 / s.step_ms + 0.5);
}

/// "NAME --set duration_s=S": the arguments of a check run.
inline std::string checkArgs(const ShippedScenario& s) {
  std::ostringstream out;
  out << s.name << " --set duration_s=" << s.check_s;
  return out.str();
}

}  // namespace climbsim::system_test
