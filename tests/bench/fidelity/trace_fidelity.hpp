#pragma once
/// @file
/// Fidelity figures of a run's trace.csv (docs/benchmarks.md#fidelity): how much a strip's leak
/// area jumps from one depth frame to the next, how much the downforce ripples about its moving
/// mean, and window means, from the columns `t_s`, `downforce_n` and `leak_area_m2_<segment>`.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace climbsim::bench {

/// A trace.csv by columns: names[k] and values[k][row].
struct Trace {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;

  /// The values of column `name`; std::runtime_error naming it when the trace has none.
  const std::vector<double>& column(const std::string& name) const {
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (names[k] == name) return values[k];
    }
    throw std::runtime_error("trace.csv: no column '" + name + "'");
  }
  /// Rows whose t_s lies in [t0_s, t1_s].
  std::vector<std::size_t> rowsIn(double t0_s, double t1_s) const {
    std::vector<std::size_t> rows;
    const auto& t = column("t_s");
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] >= t0_s && t[i] <= t1_s) rows.push_back(i);
    }
    return rows;
  }
};

/// Reads `path` (a header line, then one row of numbers per line).
inline Trace readTrace(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  Trace trace;
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) trace.names.push_back(name);
  trace.values.resize(trace.names.size());
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    std::stringstream cells(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(cells, cell, ',') && k < trace.names.size(); ++k) {
      trace.values[k].push_back(std::stod(cell));
    }
    if (k != trace.names.size()) throw std::runtime_error(path + ":" + std::to_string(number) + ": too few cells");
  }
  return trace;
}

/// One strip's frame-to-frame leak change over a window.
struct LeakJump {
  std::string segment;
  double jump_max_m2 = 0.0;  ///< largest |L(row + 1) - L(row)| in the window [m^2]
  double jump_t_s = 0.0;     ///< t_s of the row after it
  /// Largest |change - its trend| in the window [m^2]: a frame's change less the mean change
  /// per frame over the rows within +-trend_window_s / 2 (a steady rise or fall, as when the
  /// crack moves from one segment's part of the strip into its neighbour's, is no jump).
  double about_trend_max_m2 = 0.0;
  double about_trend_t_s = 0.0;
  double mean_m2 = 0.0;      ///< mean L over the window's rows [m^2]
  double relative() const { return mean_m2 > 0.0 ? jump_max_m2 / mean_m2 : 0.0; }
  double relativeAboutTrend() const { return mean_m2 > 0.0 ? about_trend_max_m2 / mean_m2 : 0.0; }
};

/// The strips that lie over a gap all the while in [t0_s, t1_s]: their leak area is more than
/// twice the closed sealing's (row 0 holds the initial, closed leak areas) at every row of the
/// window; each with its largest change between consecutive rows (the leakage is held between
/// depth frames, so these are the changes from one frame to the next), and the largest change
/// about its trend.
inline std::vector<LeakJump> leakJumps(const Trace& trace, double t0_s, double t1_s, double trend_window_s) {
  const std::string prefix = "leak_area_m2_";
  const auto rows = trace.rowsIn(t0_s, t1_s);
  const auto& t = trace.column("t_s");
  std::vector<LeakJump> jumps;
  for (std::size_t k = 0; k < trace.names.size(); ++k) {
    if (trace.names[k].rfind(prefix, 0) != 0 || rows.empty()) continue;
    const auto& leak = trace.values[k];
    LeakJump j;
    j.segment = trace.names[k].substr(prefix.size());
    bool over = true;
    for (std::size_t n = 0; n < rows.size(); ++n) {
      over = over && leak[rows[n]] > 2.0 * leak[0];
      j.mean_m2 += leak[rows[n]];
      if (n == 0) continue;
      const std::size_t i = rows[n];
      const double change = leak[i] - leak[i - 1];
      if (std::abs(change) > j.jump_max_m2) {
        j.jump_max_m2 = std::abs(change);
        j.jump_t_s = t[i];
      }
      if (change == 0.0) continue;  // between frames: the leakage is held
      // The trend: the mean change per frame (the changes of the rows within the window, over
      // the frames among them).
      double sum = 0.0;
      std::size_t frames = 0;
      for (std::size_t k = 1; k < t.size(); ++k) {
        if (std::abs(t[k] - t[i]) > 0.5 * trend_window_s + 1e-9) continue;
        sum += leak[k] - leak[k - 1];
        frames += leak[k] != leak[k - 1] ? 1 : 0;
      }
      const double about = std::abs(change - (frames > 0 ? sum / static_cast<double>(frames) : 0.0));
      if (about > j.about_trend_max_m2) {
        j.about_trend_max_m2 = about;
        j.about_trend_t_s = t[i];
      }
    }
    j.mean_m2 /= static_cast<double>(rows.size());
    if (over) jumps.push_back(j);
  }
  return jumps;
}

/// The rms of f about its centred moving mean over `window_s` (the rows within +-window_s / 2
/// of each row), over the rows of [t0_s, t1_s].
inline double rippleAboutMovingMean(const std::vector<double>& t, const std::vector<double>& f, double t0_s,
                                    double t1_s, double window_s) {
  double sum2 = 0.0;
  std::size_t rows = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < t0_s || t[i] > t1_s) continue;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t j = 0; j < t.size(); ++j) {
      if (std::abs(t[j] - t[i]) <= 0.5 * window_s + 1e-9) {
        sum += f[j];
        ++count;
      }
    }
    const double d = f[i] - sum / static_cast<double>(count);
    sum2 += d * d;
    ++rows;
  }
  return rows == 0 ? 0.0 : std::sqrt(sum2 / static_cast<double>(rows));
}

/// The downforce's ripple [N]: its rms about its moving mean over `window_s`, in [t0_s, t1_s].
inline double downforceRipple_n(const Trace& trace, double t0_s, double t1_s, double window_s) {
  return rippleAboutMovingMean(trace.column("t_s"), trace.column("downforce_n"), t0_s, t1_s, window_s);
}

/// The ripple [N] of the difference of two runs' downforce, F_a - F_b, row by row (the same
/// steps): what `a`'s ripple has that `b`'s has not, e.g. a coarse image's against the finest's.
inline double downforceDifferenceRipple_n(const Trace& a, const Trace& b, double t0_s, double t1_s,
                                          double window_s) {
  const auto& fa = a.column("downforce_n");
  const auto& fb = b.column("downforce_n");
  const std::size_t n = std::min(fa.size(), fb.size());
  std::vector<double> t(a.column("t_s").begin(), a.column("t_s").begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = fa[i] - fb[i];
  return rippleAboutMovingMean(t, d, t0_s, t1_s, window_s);
}

/// Mean over the rows of [t0_s, t1_s] of the sum of the columns `names`.
inline double windowMean(const Trace& trace, const std::vector<std::string>& names, double t0_s, double t1_s) {
  const auto rows = trace.rowsIn(t0_s, t1_s);
  double sum = 0.0;
  for (const std::string& name : names) {
    const auto& v = trace.column(name);
    for (const std::size_t i : rows) sum += v[i];
  }
  return rows.empty() ? 0.0 : sum / static_cast<double>(rows.size());
}

}  // namespace climbsim::bench
