// run.mcap as the recorder and solo write it (node/run_recording.hpp): a channel per recorded
// topic, each sample once, as its type support serialises it.

#include "node/run_recording.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <mcap/reader.hpp>

#include <cstring>
#include <filesystem>

#include "climbsim/recording/mcap_check.hpp"
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

}  // namespace
}  // namespace climbsim::recorder
