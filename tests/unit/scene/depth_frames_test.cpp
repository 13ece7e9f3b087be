// Which depth frames the default run renders whole (services/scene/model/depth_frames.hpp): the
// depth grid's (the first frame at or after each 0.1 s), the sealing pictures' (the frame the
// sealing reads at the first of its steps at or after each requested time), every frame with
// recording.depth_images, every frame without a mask; the rest at the sealing's pixels.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "depth_frames.hpp"
#include "scene_translate.hpp"

namespace climbsim::scene {
namespace {

constexpr std::int64_t kMs = 1'000'000;

/// The frames among `count` frames of `period_ns` (from t = 0) that `choice` renders whole.
std::vector<int> wholeFrames(const DepthFrameChoice& choice, std::int64_t period_ns, int count) {
  WholeDepthFrames frames(choice);
  std::vector<int> whole;
  for (int k = 0; k < count; ++k) {
    if (frames.whole(k * period_ns)) whole.push_back(k);
  }
  return whole;
}

DepthFrameChoice masked() {
  DepthFrameChoice choice;
  choice.robot_file = "robot.yaml";
  choice.read_lag_ns = 5 * kMs;
  return choice;
}

TEST(WholeDepthFrames, TheDepthGridsFramesAreWhole) {
  // 50 frames/s: every fifth frame (0.1 s apart), from the first.
  EXPECT_EQ(wholeFrames(masked(), 20 * kMs, 16), (std::vector<int>{0, 5, 10, 15}));
  // 30 ms frames: the first at or after each multiple of 0.1 s (0, 0.12, 0.21, 0.3).
  EXPECT_EQ(wholeFrames(masked(), 30 * kMs, 11), (std::vector<int>{0, 4, 7, 10}));
  // Frames further apart than 0.1 s: every one.
  EXPECT_EQ(wholeFrames(masked(), 250 * kMs, 4), (std::vector<int>{0, 1, 2, 3}));
  static_assert(DepthGridSchedule::kInterval_ns == WholeDepthFrames::kWholeInterval_ns, "the grid's frames");
}

TEST(WholeDepthFrames, WithoutDepthGridsOnlyThePicturesFramesAreWhole) {
  DepthFrameChoice choice = masked();
  choice.depth_grids = false;
  EXPECT_EQ(wholeFrames(choice, 20 * kMs, 16), (std::vector<int>{}));
  choice.read_at_s = {0.043, 0.2};
  EXPECT_EQ(wholeFrames(choice, 20 * kMs, 16), (std::vector<int>{2, 10}));
}

TEST(WholeDepthFrames, TheFrameTheSealingReadsForAPictureIsWhole) {
  DepthFrameChoice choice = masked();
  // Read one 5 ms step after each frame: a picture at 0.043 s is taken at the sealing's step at
  // 0.045 s from the frame of 0.04 s; at 0.065 s exactly, from the frame of 0.06 s; at 0.0651 s
  // from the next one (0.08 s); 0.1 s is the grid's.
  choice.read_at_s = {0.065, 0.043, 0.0651};
  EXPECT_EQ(wholeFrames(choice, 20 * kMs, 6), (std::vector<int>{0, 2, 3, 4, 5}));
  choice.read_at_s = {0.0};  // the first frame (whole as the grid's too)
  EXPECT_EQ(wholeFrames(choice, 20 * kMs, 3), (std::vector<int>{0}));
}

TEST(WholeDepthFrames, EveryFrameWholeWhenRecordedOrWithoutAMask) {
  DepthFrameChoice recorded = masked();
  recorded.every_frame_whole = true;
  EXPECT_FALSE(recorded.masked());
  EXPECT_EQ(wholeFrames(recorded, 20 * kMs, 4), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(DepthFrameChoice{}.masked());
  EXPECT_EQ(wholeFrames(DepthFrameChoice{}, 20 * kMs, 4), (std::vector<int>{0, 1, 2, 3}));
}

}  // namespace
}  // namespace climbsim::scene
