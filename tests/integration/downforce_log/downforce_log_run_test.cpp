// climbsim-downforce-log beside a real run: `climbsim-compose run crack-descent -f
// deploy/compose.downforce-log.yaml --viewer` (observers start with --viewer) for 5 s of
// simulated time. Its lines (logs/downforce_log.log) come one per second of simulated time,
// each at the first sample it received at or after the whole second, and each says the F and
// set-point trace.csv has at the line's time, to the digits it prints. Nothing here depends on
// wall time: the run's and the log's pace may be whatever the machine's load makes them.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream out;
  out << in.rdbuf();
  return out.str();
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, separator);) parts.push_back(part);
  return parts;
}

std::string printed(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

/// A row of trace.csv: F and the set-point [N].
struct TraceRow {
  double downforce_n;
  double setpoint_n;
};

/// trace.csv's rows by their time in whole milliseconds.
std::map<long long, TraceRow> traceByMs(const fs::path& file) {
  const auto lines = split(readFile(file), '\n');
  std::map<long long, TraceRow> rows;
  if (lines.empty()) return rows;
  const auto header = split(lines[0], ',');
  const auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return i;
    }
    ADD_FAILURE() << "trace.csv has no column " << name;
    return std::size_t{0};
  };
  const std::size_t t = column("t_s");
  const std::size_t f = column("downforce_n");
  const std::size_t setpoint = column("downforce_setpoint_n");
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto cells = split(lines[i], ',');
    if (cells.size() != header.size()) continue;
    rows[std::llround(std::stod(cells[t]) * 1000.0)] = {std::stod(cells[f]), std::stod(cells[setpoint])};
  }
  return rows;
}

/// One line of the log.
struct LogLine {
  std::string t_s;         ///< as printed, "3.000"
  std::string F_n;         ///< "2187.4"
  std::string setpoint_n;  ///< "2200", or "" for "no set-point"
  std::string text;
};

std::vector<LogLine> logLines(const fs::path& file) {
  static const std::regex pattern(R"(t = (\d+\.\d{3}) s: F = (-?\d+\.\d) N \((?:set-point (\d+) N|no set-point)\))");
  std::vector<LogLine> lines;
  for (const auto& line : split(readFile(file), '\n')) {
    std::smatch m;
    if (std::regex_search(line, m, pattern)) lines.push_back({m[1], m[2], m[3], line});
  }
  return lines;
}

TEST(DownforceLogRun, LogsTheTracesDownforceOnceASecondOfSimulatedTime) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "downforce-log";
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  const std::string root = CLIMBSIM_ROOT;
  const std::string command = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose --root " + root + " --build " +
                              CLIMBSIM_BUILD_DIR + " run crack-descent -f " + root +
                              "/deploy/compose.downforce-log.yaml --viewer --set duration_s=5 --out " + dir.string() +
                              " > " + dir.string() + ".log 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(dir.string() + ".log");

  const auto trace = traceByMs(dir / "trace.csv");
  ASSERT_GE(trace.size(), 1000u) << "5 s of 5 ms steps";
  const auto lines = logLines(dir / "logs" / "downforce_log.log");
  // The log's reader is created once the run is under way (DownforceReader: its first samples
  // are not seen), so its first line may be that of the second second. The last step's value,
  // which holds at 5 s, is not on the topic (no roster member reads it): the last line is 4 s's.
  ASSERT_GE(lines.size(), 3u) << readFile(dir / "logs" / "downforce_log.log");
  long long previous_second = -1;
  for (const auto& line : lines) {
    const long long ms = std::llround(std::stod(line.t_s) * 1000.0);
    const long long second = ms / 1000;
    if (previous_second < 0) {
      EXPECT_LE(second, 2) << "the first line comes in the first or second second: " << line.text;
    } else {
      EXPECT_EQ(second, previous_second + 1) << "one line per second: " << line.text;
    }
    previous_second = second;
    // The first sample at or after the whole second: a few missed samples (best effort) at most.
    EXPECT_LT(ms % 1000, 500) << line.text;
    const auto row = trace.find(ms);
    ASSERT_NE(row, trace.end()) << "no trace row at " << line.t_s << " s: " << line.text;
    EXPECT_EQ(line.F_n, printed("%.1f", row->second.downforce_n)) << line.text;
    EXPECT_EQ(line.setpoint_n, row->second.setpoint_n > 0 ? printed("%.0f", row->second.setpoint_n) : "")
        << line.text;
  }
  EXPECT_EQ(previous_second, 4) << "the lines go on to the run's end";
}

}  // namespace
