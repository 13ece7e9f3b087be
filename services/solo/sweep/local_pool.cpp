#include "local_pool.hpp"

#include <csignal>
#include <filesystem>

#include "climbsim/errors.hpp"

namespace climbsim::sweep {

LocalPool::LocalPool(std::vector<VariantJob> jobs, unsigned at_a_time)
    : waiting_(jobs.begin(), jobs.end()), at_a_time_(at_a_time > 0 ? at_a_time : 1) {}

std::vector<VariantEnd> LocalPool::poll() {
  namespace fs = std::filesystem;
  while (!waiting_.empty() && running_.size() < at_a_time_) {
    VariantJob job = std::move(waiting_.front());
    waiting_.pop_front();
    fs::remove_all(job.dir);
    ProcessSpec spec;
    spec.argv = job.argv;
    spec.output_file = job.dir + ".log";
    fs::remove(spec.output_file);
    auto process = std::make_unique<ChildProcess>(spec);
    running_.push_back({std::move(job), std::move(process), std::chrono::steady_clock::now(), false});
  }
  std::vector<VariantEnd> ended;
  for (auto it = running_.begin(); it != running_.end();) {
    const auto code = it->process->poll();
    if (!code) {
      ++it;
      continue;
    }
    VariantEnd end;
    end.index = it->job.variant.index;
    end.exit_code = *code;
    end.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->started).count();
    end.stopped = *code == kExitStopped || (it->signalled && *code != kExitOk && *code != kExitFell);
    ended.push_back(end);
    it = running_.erase(it);
  }
  return ended;
}

void LocalPool::stop() {
  waiting_.clear();
  for (auto& r : running_) {
    if (!r.signalled) r.process->signal(SIGINT);
    r.signalled = true;
  }
}

}  // namespace climbsim::sweep
