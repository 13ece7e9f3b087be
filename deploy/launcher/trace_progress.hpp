#pragma once
/// @file
/// The live progress of a run, read from the trace the recorder appends to (one flushed row
/// per step): simulation time, real-time factor and downforce, as one line for the terminal.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
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

/// The real-time factor of a run from the rows its trace shows: simulated seconds per wall
/// second from the first row seen to the newest one. While the run goes on the wall time runs
/// to now (a stalled or paused run slows down); once it has ended, to the moment its last row
/// came: the final line keeps the run's overall rate while the launcher waits for the other
/// processes (a viewer) to end, instead of falling towards 0.0x.
class RateMeter {
 public:
  /// The newest row of a poll at wall time `wall_s` [s] (any fixed origin), at simulation time `t_s`.
  void see(double wall_s, double t_s);
  /// Nothing before two rows 0.2 s of wall time apart; `ended`: the run has ended.
  std::optional<double> rate(double now_wall_s, bool ended) const;

 private:
  std::optional<std::pair<double, double>> first_;  ///< wall and simulation time of the first row
  std::optional<std::pair<double, double>> last_;   ///< of the newest row, when it came
};

/// "t 12.35/20 s (62%)  3.4x real time  F 2186 N  running": `rtf` is sim seconds per wall
/// second (nothing before two samples), `duration_s` 0 if unknown.
std::string progressText(const std::optional<TraceSample>& sample, double duration_s, std::optional<double> rtf,
                         const std::string& state);

}  // namespace climbsim::launcher
