#pragma once
/// @file
/// Where the variants of a sweep run: a pool takes every variant's command at once and reports
/// each variant's end. LocalPool runs them as child processes of this machine, N at a time;
/// RayPool hands them to a Ray cluster (ray_pool.hpp). The sweep reads the run directories the
/// same way whichever pool ran them.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sweep_spec.hpp"

namespace climbsim::sweep {

/// One variant to run: its command writes its run directory `dir` and its output to dir.log.
struct VariantJob {
  Variant variant;
  std::vector<std::string> argv;  ///< argv[0]: a program of the build (same path on every machine)
  std::string dir;                ///< the variant's run directory, DIR/<variant name>
};

/// How a variant's run ended.
struct VariantEnd {
  std::size_t index = 0;           ///< Variant::index
  std::optional<int> exit_code;    ///< none: it never ended by itself (lost beyond its retries)
  bool stopped = false;            ///< stopped on request before its end: left out of sweep.csv
  double wall_s = 0.0;             ///< wall time of the variant's process [s]
  std::string note;                ///< why there is no exit code ("" otherwise)
};

/// Variants running and waiting.
struct PoolLoad {
  std::size_t running = 0;
  std::size_t queued = 0;
};

/// Runs a sweep's variants.
class VariantPool {
 public:
  virtual ~VariantPool() = default;
  /// Starts what has room and returns the variants that ended since the last call.
  virtual std::vector<VariantEnd> poll() = 0;
  /// True once every variant has ended (or, after stop(), every one under way).
  virtual bool finished() const = 0;
  virtual PoolLoad load() const = 0;
  /// Ctrl-C: no variant starts any more; those under way are asked to stop.
  virtual void stop() = 0;
  /// A failure of the pool itself that ends the sweep (one line), once it happened.
  virtual std::optional<std::string> fatal() const { return std::nullopt; }
};

}  // namespace climbsim::sweep
