#pragma once
/// @file
/// The variants of a sweep as tasks of a Ray cluster: a child process runs the Ray driver
/// (ray_driver.py, `climbsim-ray-sweep`, in the build's Python environment) with every variant
/// at once; Ray places each on a node with the CPUs it reserves and retries it elsewhere when
/// its worker is lost. The driver puts each finished variant's run directory and log into the
/// sweep directory, as a local variant leaves them, and tells this pool one JSON line per event
/// on its standard output:
///   {"ended": I, "exit_code": C, "wall_s": W, "node": "ADDRESS"}   variant I ran to its exit code
///   {"lost": I, "reason": "..."}     variant I did not run to an end (lost beyond its retries)
///   {"load": {"running": R, "queued": Q}}
///   {"fatal": "..."}                 the sweep cannot go on (a node without the checkout, ...)
/// Other lines are the driver's own words, passed on to stderr.

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "climbsim/process.hpp"
#include "variant_pool.hpp"

namespace climbsim::sweep {

struct RayOptions {
  std::string driver;            ///< the driver program (<build>/bin/climbsim-ray-sweep)
  std::string address;           ///< the cluster: HOST:PORT, or auto
  double cpus_per_variant = 1;   ///< CPUs a variant's task reserves
  std::string out_dir;           ///< the sweep directory
  std::string root;              ///< the checkout every node must have at the same path
  std::vector<std::string> needs;  ///< files every node must have besides (the scenario file, ...)
  std::string address_file;      ///< where `cluster up` leaves the address `auto` stands for
};

class RayPool : public VariantPool {
 public:
  /// Starts the driver with every job; throws ConfigError if the driver is missing.
  RayPool(const std::vector<VariantJob>& jobs, const RayOptions& options);
  ~RayPool() override;
  std::vector<VariantEnd> poll() override;
  bool finished() const override { return driver_done_; }
  PoolLoad load() const override { return load_; }
  /// SIGINT to the driver: it cancels the tasks; every variant not ended counts as stopped.
  void stop() override;
  std::optional<std::string> fatal() const override { return fatal_; }

 private:
  void handle(const std::string& line, std::vector<VariantEnd>& ended);

  std::unique_ptr<ChildProcess> driver_;
  int read_fd_ = -1;
  std::string request_file_;
  std::string partial_;
  std::set<std::size_t> open_;  ///< variants not ended yet
  PoolLoad load_;
  std::optional<std::string> fatal_;
  bool stopping_ = false;
  bool driver_done_ = false;
};

}  // namespace climbsim::sweep
