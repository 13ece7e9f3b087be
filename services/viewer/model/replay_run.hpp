#pragma once
/// @file
/// A finished run directory for replay (`climbsim view RUN_DIR`): its trace.csv as columns,
/// its summary.json and the sealing pictures it holds.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace climbsim::viewer {

/// trace.csv as columns: {"columns": [names], "values": [[column 0 ...], [column 1 ...], ...]}.
/// Throws ConfigError with one line "<file>:<line>: column <name> = <cell>: <problem>" for a
/// missing file, an empty header, a short or long row or a cell that is not a number; a last
/// line cut off mid-row (a run killed while writing) is left out.
nlohmann::json loadTraceColumns(const std::string& trace_csv);

/// The sealing pictures of RUN_DIR/pictures: [{"kind": "edges"|"gaps", "t_s", "file"}] sorted
/// by time, parsed from the names sealing_<kind>_<t>s.png; other files are ignored.
nlohmann::json listSealingPictures(const std::string& run_dir);

}  // namespace climbsim::viewer
