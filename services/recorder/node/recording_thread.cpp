#include "node/recording_thread.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <utility>

namespace climbsim::recorder {

RecordingThread::RecordingThread(std::unique_ptr<RunRecording> recording)
    : recording_(std::move(recording)), thread_([this] { loop(); }) {}

RecordingThread::~RecordingThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ending_ = true;
  }
  work_.notify_one();
  thread_.join();
}

void RecordingThread::throwIfFailed() {
  if (failure_) std::rethrow_exception(failure_);
}

void RecordingThread::post(Job job) {
  bool wake = false;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    throwIfFailed();
    done_.wait(lock, [this] { return jobs_.size() < kMaxQueued || failure_; });
    throwIfFailed();
    jobs_.push_back(std::move(job));
    wake = jobs_.size() == kWakeJobs;
  }
  if (wake) work_.notify_one();
}

void RecordingThread::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  draining_ = true;
  work_.notify_one();
  done_.wait(lock, [this] { return jobs_.empty() && !running_job_; });
  draining_ = false;
  throwIfFailed();
}

void RecordingThread::loop() {
  // This thread only (a thread id is a process id to setpriority); a refusal leaves it as it was.
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), kNice);
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    // Woken by a batch of jobs, a drain or the end; jobs fewer than a batch wait at most kMaxDelay.
    work_.wait_for(lock, kMaxDelay,
                   [this] { return (!jobs_.empty() && (jobs_.size() >= kWakeJobs || draining_)) || ending_; });
    if (jobs_.empty()) {
      if (ending_) return;
      continue;
    }
    while (!jobs_.empty()) {
      Job job = std::move(jobs_.front());
      jobs_.pop_front();
      running_job_ = true;
      lock.unlock();
      std::exception_ptr failed;
      try {
        job(*recording_);
      } catch (...) {
        failed = std::current_exception();
      }
      lock.lock();
      running_job_ = false;
      if (failed && !failure_) failure_ = failed;
    }
    done_.notify_all();  // room for a waiting post(), or a drain that is over
  }
}

}  // namespace climbsim::recorder
