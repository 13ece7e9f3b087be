#pragma once
/// @file
/// The wall under the robot kept for replays: depth grids (height_grid.hpp) at most every
/// `interval` of simulated time, one JSON line each (heightGridJson), in RUN_DIR/viewer/
/// depth_grids.jsonl. The live viewer writes it (best effort: it sees what its KEEP_LAST 1
/// reader gets); `view RUN_DIR` serves the grid in force at the slider's time.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace climbsim {

/// Where the grids of a run directory are.
std::string gridRecordPath(const std::string& run_dir);

class GridRecorder {
 public:
  /// Appends to `path` (its directory is made); `interval_ns` > 0 of simulated time between lines.
  GridRecorder(const std::string& path, std::int64_t interval_ns);

  /// Writes `json_line` (one depth message) if t_ns is at least the interval after the last
  /// written one (or it is the first); returns whether it did.
  bool offer(std::int64_t t_ns, const std::string& json_line);

 private:
  std::ofstream out_;
  std::int64_t interval_ns_;
  std::int64_t last_t_ns_ = 0;
  bool any_ = false;
};

/// The recorded grids: (t [s], JSON text), in file order. Empty if there is no file; a line
/// that is not a depth message with a numeric t_s is skipped (a run killed mid-line).
std::vector<std::pair<double, std::string>> loadGridRecords(const std::string& path);

/// The text of the last record with t <= t_s (the first if none); "" if there are none.
const std::string& gridAt(const std::vector<std::pair<double, std::string>>& records, double t_s);

}  // namespace climbsim
