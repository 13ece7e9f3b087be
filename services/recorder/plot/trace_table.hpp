#pragma once
/// @file
/// trace.csv of a run directory as columns of doubles (recorder/node/trace_recorder.hpp writes
/// it: a header line of column names, then one row of numbers per step). Every problem is a
/// climbsim::ConfigError with one line naming the file, the line and column, and the value.

#include <cstddef>
#include <string>
#include <vector>

namespace climbsim::plot {

class TraceTable {
 public:
  /// Reads `path`. ConfigError if the file cannot be read, has no header, a row has another
  /// number of cells than the header, or a cell is not a number (strtod must consume it whole;
  /// "nan" and "inf" are accepted, the plots leave such points out).
  static TraceTable read(const std::string& path);
  /// The same from text (tests); `source` names it in messages.
  static TraceTable parse(const std::string& text, const std::string& source);

  const std::string& source() const { return source_; }
  const std::vector<std::string>& names() const { return names_; }
  std::size_t rows() const { return rows_; }
  bool has(const std::string& name) const;
  /// The column `name`; ConfigError "<file>: no column '<name>' (header: ...)" if absent.
  const std::vector<double>& column(const std::string& name) const;
  /// The row whose t_s is nearest to `t_s` (the first of equals); ConfigError without rows.
  std::size_t rowNearest(double t_s) const;

 private:
  std::string source_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
  std::size_t rows_ = 0;
};

}  // namespace climbsim::plot
