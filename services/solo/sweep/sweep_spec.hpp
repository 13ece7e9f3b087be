#pragma once
/// @file
/// What `climbsim sweep` runs (no processes here): the swept keys with their values from
/// `--set KEY=V1,V2,...`, the cartesian product of them, and each variant's overrides and
/// directory name. Everything is checked before any variant starts.

#include <cstddef>
#include <string>
#include <vector>

namespace climbsim::sweep {

/// One `--set KEY=V1,V2,...`: a scenario key (dotted path, as --set of run) and its values.
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;  ///< YAML scalars or flow collections, in the order given
};

/// Splits `--set KEY=V1,V2,...` at the commas outside [], {} and quotes (so `drive.1={t_s: 2,
/// vx_mps: 0.05}` is one value). ConfigError, one line naming the option and value, for a
/// missing '=', an empty key, an empty list (an empty product), an empty value, unbalanced
/// brackets or quotes.
SweepAxis parseAxis(const std::string& option);

/// One run of the sweep: a value of every axis.
struct Variant {
  std::size_t index = 0;                 ///< 0-based, in product order (the last axis varies fastest)
  std::vector<std::string> values;       ///< one per axis
  std::vector<std::string> overrides;    ///< "KEY=VALUE" per axis, for --set
  std::string name;                      ///< directory name: "003_key=value__key2=value2", safe characters
};

/// The cartesian product of the axes. ConfigError if there is no axis, a key is swept twice,
/// or the product exceeds `max_variants`.
std::vector<Variant> variantsOf(const std::vector<SweepAxis>& axes, std::size_t max_variants = 10000);

}  // namespace climbsim::sweep
