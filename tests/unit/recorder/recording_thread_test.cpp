// run.mcap written off the recorder's step thread (node/recording_thread.hpp): the jobs run in
// the order posted, a row posted after a step's samples is written once their chunk is closed,
// and a failed write is thrown again on the posting thread without losing the jobs after it.

#include "node/recording_thread.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "climbsim/recording/mcap_check.hpp"

namespace climbsim::recorder {
namespace {
namespace fs = std::filesystem;

fs::path tempMcap(const std::string& name) {
  return fs::path(testing::TempDir()) / ("climbsim_" + name + "_" + std::to_string(::getpid()) + ".mcap");
}

/// A recording of the default inputs at `path`, as the recorder makes it.
std::unique_ptr<RunRecording> recordingAt(const fs::path& path) {
  return std::make_unique<RunRecording>(path.string(), RecordedInputs{}, false, RecordingFiles{"", "", "", "recorder"});
}

climbsim::AdhesionForce force(std::uint64_t step) {
  climbsim::AdhesionForce f;
  f.source("thermo");
  f.step(step);
  f.t_ns(static_cast<std::int64_t>(step) * 5'000'000);
  f.downforce_n(100.0 + static_cast<double>(step));
  return f;
}

TEST(RecordingThread, JobsRunInOrderAndARowFollowsTheChunkBeforeIt) {
  const fs::path path = tempMcap("recording_thread");
  std::vector<std::string> rows;  // what the rows saw: the file's closed chunks when each ran
  {
    RecordingThread thread(recordingAt(path));
    for (std::uint64_t k = 0; k < 450; ++k) {
      const std::int64_t t_ns = static_cast<std::int64_t>(k) * 5'000'000;
      thread.post([t_ns, f = std::vector<climbsim::AdhesionForce>{force(k)}](RunRecording& r) {
        r.update(t_ns, {}, f, {}, {}, {});
      });
      if (k == 200 || k == 400) {  // the first rows of simulated seconds 1 and 2
        thread.post([&rows, &path, k](RunRecording&) {
          const auto check = recording::checkMcap(path.string());
          rows.push_back(std::to_string(k) + ":" + std::to_string(check.channels.count("thermo/AdhesionForce")
                                                                      ? check.channels.at("thermo/AdhesionForce").messages
                                                                      : 0));
        });
      }
    }
    thread.post([](RunRecording& r) { r.finish({{"steps", 450}}); });
    thread.drain();
  }
  // Row 200 (t = 1 s) runs after the chunk of second 0 (steps 0..199) is on the file.
  EXPECT_EQ(rows, (std::vector<std::string>{"200:200", "400:400"}));
  const auto check = recording::checkMcap(path.string());
  ASSERT_TRUE(check.closed) << check.problem;
  EXPECT_EQ(check.channels.at("thermo/AdhesionForce").messages, 450u);
  fs::remove(path);
}

TEST(RecordingThread, FewerJobsThanABatchRunAtADrainAndTheThreadGoesOnAfterIt) {
  const fs::path path = tempMcap("recording_thread_drain");
  int rows = 0;
  {
    RecordingThread thread(recordingAt(path));
    for (int round = 1; round <= 3; ++round) {
      for (int k = 0; k < 3; ++k) thread.post([&rows](RunRecording&) { ++rows; });
      thread.drain();
      EXPECT_EQ(rows, 3 * round);
    }
  }
  fs::remove(path);
}

TEST(RecordingThread, AFailedJobIsThrownAgainAndTheJobsAfterItStillRun) {
  const fs::path path = tempMcap("recording_thread_failure");
  int rows = 0;
  {
    RecordingThread thread(recordingAt(path));
    thread.post([](RunRecording&) { throw std::runtime_error("run.mcap: disk full"); });
    thread.post([&rows](RunRecording&) { ++rows; });
    try {
      thread.drain();
      FAIL() << "the failure was not thrown again";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "run.mcap: disk full");
    }
    EXPECT_EQ(rows, 1) << "the row after the failed write still ran";
    EXPECT_THROW(thread.post([&rows](RunRecording&) { ++rows; }), std::runtime_error);
    EXPECT_THROW(thread.drain(), std::runtime_error) << "the first failure, again";
  }
  fs::remove(path);
}

}  // namespace
}  // namespace climbsim::recorder
