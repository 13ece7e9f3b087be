// run.mcap as the recorder and solo write it (node/run_recording.hpp): a channel per recorded
// topic, each sample once, as its type support serialises it.

#include "node/run_recording.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <mcap/reader.hpp>

#include <cstring>
#include <filesystem>

#include "climbsim/recording/mcap_check.hpp"
#include "scenePubSubTypes.h"
#include "thermoPubSubTypes.h"

namespace climbsim::recorder {
namespace {
namespace fs = std::filesystem;

climbsim::AdhesionForce force(const std::string& source, std::uint64_t step, double downforce_n) {
  climbsim::AdhesionForce f;
  f.source(source);
  f.step(step);
  f.t_ns(static_cast<std::int64_t>(step) * 5'000'000);
  f.downforce_n(downforce_n);
  return f;
}

TEST(RunRecording, EverySampleOnceWithTheBytesADdsReaderGets) {
  const fs::path path = fs::path(testing::TempDir()) / ("climbsim_run_recording_" + std::to_string(::getpid()) + ".mcap");
  RecordedInputs inputs;
  inputs.leakage = false;
  {
    RunRecording recording(path.string(), inputs, false, {"", "", "", "solo"});
    climbsim::RunStart start;
    start.dt_ns(5'000'000);
    recording.runStart(start);
    // The held sample of a producer due every other step is read twice: written once.
    for (std::uint64_t k = 0; k < 400; ++k) {
      const std::int64_t t_ns = static_cast<std::int64_t>(k) * 5'000'000;
      std::vector<climbsim::AdhesionForce> forces = {force("thermo", k == 0 ? 0 : k - 1, 100.0 + k),
                                                     force("slow", k < 2 ? 0 : (k - 1) / 2 * 2, 1.0)};
      if (k == 1) forces[0].downforce_n(100.0);  // equal to the initial state: the same bytes, not again
      recording.update(t_ns, {}, forces, {}, {}, {});
    }
    climbsim::Stop stop;
    stop.t_ns(2'000'000'000);
    recording.stop(stop);
    recording.finish({{"steps", 400}});
  }
  const auto check = recording::checkMcap(path.string());
  ASSERT_TRUE(check.closed) << check.problem;
  EXPECT_EQ(check.channels.at("clock/RunStart").messages, 1u);
  EXPECT_EQ(check.channels.at("clock/Stop").messages, 1u);
  EXPECT_EQ(check.channels.at("thermo/AdhesionForce").messages, 399u + 200u);
  EXPECT_EQ(check.channels.at("thermo/ChamberState").messages, 0u);
  EXPECT_EQ(check.channels.count("sealing/Leakage"), 0u);
  EXPECT_GE(check.chunks, 2u) << "a chunk closes every simulated second";
  EXPECT_EQ(check.metadata, 2u) << "run and summary";

  // The first message is the initial state, serialised as Fast DDS serialises it for a writer.
  mcap::McapReader reader;
  ASSERT_TRUE(reader.open(path.string()).ok());
  AdhesionForcePubSubType type;
  for (const auto& view : reader.readMessages()) {
    if (view.channel->topic != "thermo/AdhesionForce") continue;
    auto expected = force("thermo", 0, 100.0);
    eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&expected)());
    ASSERT_TRUE(type.serialize(&expected, &payload));
    ASSERT_EQ(view.message.dataSize, payload.length);
    EXPECT_EQ(std::memcmp(view.message.data, payload.data, payload.length), 0);
    EXPECT_EQ(view.message.logTime, 0u);
    EXPECT_EQ(view.channel->messageEncoding, "cdr");
    EXPECT_EQ(view.schema->encoding, "omgidl");
    EXPECT_EQ(view.schema->name, "climbsim::AdhesionForce");
    break;
  }
  reader.close();
  fs::remove(path);
}

climbsim::DepthImage image(const std::string& source, std::uint64_t step, std::uint32_t side_px, float height_m) {
  climbsim::DepthImage i;
  i.source(source);
  i.step(step);
  i.t_ns(static_cast<std::int64_t>(step) * 5'000'000);
  i.width_px(side_px);
  i.height_px(side_px);
  i.pixel_size_m(0.8 / side_px);
  i.tile_rows(side_px);
  i.tile_cols(side_px);
  i.height_m().assign(static_cast<std::size_t>(side_px) * side_px, height_m);
  i.height_m()[0] = -0.01f;  // the +y, -x corner
  return i;
}

TEST(RunRecording, EveryDepthImageOnceWholeAndAsAFoxgloveGrid) {
  const fs::path path = fs::path(testing::TempDir()) / ("climbsim_run_images_" + std::to_string(::getpid()) + ".mcap");
  RecordedInputs inputs;
  inputs.depth_images = true;
  const RobotGeometry geometry{};
  {
    RunRecording recording(path.string(), inputs, false, {"", "", "", "solo"}, &geometry);
    // A frame every 4 steps, read at every step after it (held): each written once.
    for (std::uint64_t k = 1; k < 20; ++k) recording.depthImages({image("scene", (k - 1) / 4 * 4, 256, 0.001f * k)});
    // A tile (a part of the image) is recorded as it came, with no Foxglove grid.
    auto tile = image("scene-tile", 0, 256, 0.0f);
    tile.tile_rows(16);
    tile.height_m().resize(16 * 256);
    recording.depthImages({tile});
    recording.finish({});
  }
  const auto check = recording::checkMcap(path.string());
  ASSERT_TRUE(check.closed) << check.problem;
  EXPECT_EQ(check.channels.at("scene/DepthImage").messages, 5u + 1u);
  EXPECT_EQ(check.channels.at("foxglove/depth_image").messages, 5u);

  mcap::McapReader reader;
  ASSERT_TRUE(reader.open(path.string()).ok());
  DepthImagePubSubType type;
  std::vector<std::uint64_t> steps;
  for (const auto& view : reader.readMessages()) {
    if (view.channel->topic == "foxglove/depth_image") {
      EXPECT_EQ(view.schema->name, "foxglove::Grid");
      EXPECT_GT(view.message.dataSize, 256u * 256u * sizeof(float));
      continue;
    }
    if (view.channel->topic != "scene/DepthImage") continue;
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(view.message.dataSize));
    std::memcpy(payload.data, view.message.data, view.message.dataSize);
    payload.length = static_cast<std::uint32_t>(view.message.dataSize);
    climbsim::DepthImage decoded;
    ASSERT_TRUE(type.deserialize(&payload, &decoded));
    EXPECT_EQ(view.message.logTime, static_cast<std::uint64_t>(decoded.t_ns()));
    if (decoded.source() == "scene") {
      steps.push_back(decoded.step());
      EXPECT_EQ(decoded.height_m().size(), 256u * 256u);
      EXPECT_EQ(decoded.height_m()[0], -0.01f);
    }
  }
  EXPECT_EQ(steps, (std::vector<std::uint64_t>{0, 4, 8, 12, 16}));
  reader.close();
  fs::remove(path);
}

}  // namespace
}  // namespace climbsim::recorder
