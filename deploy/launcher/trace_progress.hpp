#pragma once
/// @file
/// The live progress of a run, read from the trace the recorder appends to (one flushed row
/// per step): simulation time, real-time factor and downforce, as one line for the terminal.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace climbsim::launcher {

/// The last complete row of a growing trace.csv.
struct TraceSample {
  double t_s = 0.0;                    ///< simulation time of the row [s]
  std::optional<double> downforce_n;   ///< the downforce column [N], if the trace has one
  std::uint64_t rows = 0;              ///< complete rows read so far
};

/// Reads what was appended to a CSV trace since the last call. The file may not exist yet.
class TraceTail {
 public:
  explicit TraceTail(std::string path) : path_(std::move(path)) {}

  /// The newest complete row, or nothing if no row has been completed yet. A malformed row
  /// (a cell that is not a number) is skipped: the progress line never stops a run.
  std::optional<TraceSample> poll();

 private:
  void takeLine(const std::string& line);

  std::string path_;
  std::uint64_t offset_ = 0;
  std::string partial_;
  std::vector<std::string> header_;
  int t_column_ = -1;
  int downforce_column_ = -1;
  std::optional<TraceSample> last_;
  std::uint64_t rows_ = 0;
};

/// "t 12.35/20 s (62%)  3.4x real time  F 2186 N  running": `rtf` is sim seconds per wall
/// second (nothing before two samples), `duration_s` 0 if unknown.
std::string progressText(const std::optional<TraceSample>& sample, double duration_s, std::optional<double> rtf,
                         const std::string& state);

}  // namespace climbsim::launcher
