#pragma once
/// @file
/// run.mcap written on a thread of its own (docs/recordings.md#what-recording-costs): the
/// recorder's step thread hands each row's samples over and goes on to answer the clock, whose
/// horizon waits for the recorder's acknowledgements; this thread encodes the samples, writes
/// the MCAP records and compresses the chunks. Work that must follow the recording (a trace
/// row, which reaches trace.csv only once the chunk before it is on the file) is handed over
/// the same way, so it runs after everything posted before it. A job that throws does not stop
/// the others (the rows still reach trace.csv); the first failure is thrown again on the step
/// thread, which fails the run as a write on it would.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

#include "node/run_recording.hpp"

namespace climbsim::recorder {

class RecordingThread {
 public:
  /// Work on the recording, run on the thread in the order posted.
  using Job = std::function<void(RunRecording&)>;

  /// Most jobs waiting: post() waits for room beyond it (a recording that falls behind holds
  /// the step thread up rather than the memory and the run's end growing without bound).
  static constexpr std::size_t kMaxQueued = 4096;
  /// Jobs that wake the thread (a few steps' worth: one wake-up, not one per job, each a
  /// context switch on a machine whose cores the run keeps busy).
  static constexpr std::size_t kWakeJobs = 16;
  /// Longest a job waits for the thread when fewer than kWakeJobs are queued (a trace row
  /// reaches trace.csv within this and the rows' flush period, also while the run is paused).
  static constexpr std::chrono::milliseconds kMaxDelay{20};
  /// The thread's niceness: off the loop, it takes the CPU the run's step threads leave (as the
  /// live viewer does, docs/deployment.md#the-viewer), and the queue holds what it has not done yet.
  static constexpr int kNice = 10;

  /// Starts the thread that owns `recording`.
  explicit RecordingThread(std::unique_ptr<RunRecording> recording);
  /// Runs the jobs still waiting and ends the thread (a failure is not thrown again here).
  ~RecordingThread();
  RecordingThread(const RecordingThread&) = delete;
  RecordingThread& operator=(const RecordingThread&) = delete;

  /// Queues `job` (the thread takes the jobs kWakeJobs at a time, or kMaxDelay after they
  /// came). Throws again the exception of the first job that failed, if one did.
  void post(Job job);

  /// Waits until every job posted has run; throws again the exception of the first that failed.
  void drain();

 private:
  void loop();
  void throwIfFailed();  ///< with mutex_ held

  std::unique_ptr<RunRecording> recording_;
  std::mutex mutex_;
  std::condition_variable work_;  ///< jobs for the thread, a drain or the end
  std::condition_variable done_;  ///< the jobs queued so far have run
  std::deque<Job> jobs_;
  bool running_job_ = false;
  bool draining_ = false;
  bool ending_ = false;
  std::exception_ptr failure_;
  std::thread thread_;  ///< last: started once the rest is built
};

}  // namespace climbsim::recorder
