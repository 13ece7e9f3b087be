#include "node/recording_thread.hpp"

#include <utility>

namespace climbsim::recorder {

RecordingThread::RecordingThread(std::unique_ptr<RunRecording> recording)
    : recording_(std::move(recording)), thread_([this] { loop(); }) {}

RecordingThread::~RecordingThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ending_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void RecordingThread::throwIfFailed() {
  if (failure_) std::rethrow_exception(failure_);
}

void RecordingThread::post(Job job) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    throwIfFailed();
    changed_.wait(lock, [this] { return jobs_.size() < kMaxQueued || failure_; });
    throwIfFailed();
    jobs_.push_back(std::move(job));
  }
  changed_.notify_all();
}

void RecordingThread::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return jobs_.empty() && !running_job_; });
  throwIfFailed();
}

void RecordingThread::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return !jobs_.empty() || ending_; });
    if (jobs_.empty()) return;  // ending, and nothing left to do
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    running_job_ = true;
    lock.unlock();
    changed_.notify_all();  // room for a waiting post()
    std::exception_ptr failed;
    try {
      job(*recording_);
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    running_job_ = false;
    if (failed && !failure_) failure_ = failed;
    changed_.notify_all();
  }
}

}  // namespace climbsim::recorder
