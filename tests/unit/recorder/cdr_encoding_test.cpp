// CDR bytes of a sample written into a kept buffer (node/cdr_encoding.hpp): byte for byte what
// the type's Fast DDS type support gives a writer, whatever the buffer held before.

#include "node/cdr_encoding.hpp"

#include <gtest/gtest.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstdint>
#include <vector>

#include "foxglove_schemasPubSubTypes.h"
#include "robotPubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"

namespace climbsim::recorder {
namespace {

/// The bytes the type support serialises for a writer.
template <class PubSubT>
std::vector<std::uint8_t> typeSupportBytes(typename PubSubT::type sample) {
  PubSubT type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  EXPECT_TRUE(type.serialize(&sample, &payload));
  return {payload.data, payload.data + payload.length};
}

climbsim::ChamberState chambers(std::size_t n) {
  climbsim::ChamberState s;
  s.source("thermo");
  s.step(12);
  s.t_ns(60'000'000);
  for (std::size_t i = 0; i < n; ++i) s.pressure_pa().push_back(101325.0 - 1000.0 * static_cast<double>(i));
  return s;
}

/// A scene whose strings of odd lengths put alignment padding before the doubles after them.
foxglove::SceneUpdate scene(const char* id, std::size_t triangles) {
  foxglove::SceneEntity entity;
  entity.frame_id("robot");
  entity.id(id);
  entity.frame_locked(true);
  foxglove::TriangleListPrimitive t;
  t.pose().orientation().w(1.0);
  for (std::size_t i = 0; i < 3 * triangles; ++i) {
    foxglove::Point3 p;
    p.x(0.01 * static_cast<double>(i));
    p.y(-0.02 * static_cast<double>(i));
    t.points().push_back(p);
  }
  t.color().r(0.5);
  t.color().a(0.8);
  entity.triangles().push_back(t);
  foxglove::ArrowPrimitive a;
  a.shaft_length(0.1);
  entity.arrows().push_back(a);
  foxglove::SceneUpdate update;
  update.entities().push_back(entity);
  return update;
}

TEST(CdrEncoding, GivesTheTypeSupportsBytes) {
  std::vector<std::uint8_t> out;
  encodeCdr(chambers(8), out);
  EXPECT_EQ(out, typeSupportBytes<ChamberStatePubSubType>(chambers(8)));

  climbsim::Leakage leak;
  leak.source("sealing-0");
  leak.step(5);
  leak.t_ns(25'000'000);
  for (const char* name : {"outer1", "radial6_1", "c"}) {  // odd lengths: padding before the doubles
    climbsim::LeakageSegment segment;
    segment.segment(name);
    segment.leak_area_m2(1e-5);
    segment.mean_gap_m(2e-4);
    leak.segments().push_back(segment);
  }
  encodeCdr(leak, out);
  EXPECT_EQ(out, typeSupportBytes<LeakagePubSubType>(leak));

  climbsim::DriveState drive;
  drive.source("drive");
  drive.wheels().resize(3);
  drive.wheels()[1].normal_force_n(412.5);
  encodeCdr(drive, out);
  EXPECT_EQ(out, typeSupportBytes<DriveStatePubSubType>(drive));

  encodeCdr(scene("robot", 4), out);
  EXPECT_EQ(out, typeSupportBytes<foxglove::SceneUpdatePubSubType>(scene("robot", 4)));
  EXPECT_EQ(out.size() % 4, 0u) << "header and body";
}

TEST(CdrEncoding, AReusedBufferLeavesNothingOfItsLastSampleInThePadding) {
  std::vector<std::uint8_t> out;
  // A larger sample first: its bytes fill the buffer where the smaller one's padding falls.
  encodeCdr(scene("a-longer-entity-id", 40), out);
  std::fill(out.begin(), out.end(), 0xAB);
  const std::size_t capacity = out.capacity();
  encodeCdr(scene("r", 2), out);
  EXPECT_EQ(out, typeSupportBytes<foxglove::SceneUpdatePubSubType>(scene("r", 2)));
  EXPECT_EQ(out.capacity(), capacity) << "the buffer is kept, not allocated again";
  encodeCdr(chambers(3), out);
  EXPECT_EQ(out, typeSupportBytes<ChamberStatePubSubType>(chambers(3)));
}

}  // namespace
}  // namespace climbsim::recorder
