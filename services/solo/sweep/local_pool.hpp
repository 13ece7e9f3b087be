#pragma once
/// @file
/// The variants of a sweep as child processes of this machine, `jobs` at a time.

#include <chrono>
#include <deque>
#include <memory>
#include <vector>

#include "climbsim/process.hpp"
#include "variant_pool.hpp"

namespace climbsim::sweep {

class LocalPool : public VariantPool {
 public:
  LocalPool(std::vector<VariantJob> jobs, unsigned at_a_time);
  std::vector<VariantEnd> poll() override;
  bool finished() const override { return waiting_.empty() && running_.empty(); }
  PoolLoad load() const override { return {running_.size(), waiting_.size()}; }
  /// SIGINT to every variant under way: each stops after its step under way.
  void stop() override;

 private:
  struct Running {
    VariantJob job;
    std::unique_ptr<ChildProcess> process;
    std::chrono::steady_clock::time_point started;
    bool signalled = false;
  };
  std::deque<VariantJob> waiting_;
  std::vector<Running> running_;
  unsigned at_a_time_;
};

}  // namespace climbsim::sweep
