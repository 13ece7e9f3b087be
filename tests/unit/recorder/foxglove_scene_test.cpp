// The Foxglove channels' messages (node/foxglove_scene.hpp) and their schema texts.

#include "node/foxglove_scene.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "climbsim/recording/omgidl_schema.hpp"
#include "climbsim/robot/robot_description.hpp"

namespace climbsim::recorder {
namespace {

TEST(FoxgloveScene, ChambersColouredBySuctionWheelLoadsAndDownforceAsArrows) {
  const RobotGeometry geometry = computeGeometry(loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml"));
  ASSERT_EQ(geometry.chambers.size(), 7u);
  ASSERT_EQ(geometry.wheels.size(), 3u);
  climbsim::ChamberState chambers;
  // Chamber 1 at full suction, chamber 2 at half, the others and the reservoir at none.
  chambers.pressure_pa() = {100000.0 - kFullSuctionPa, 100000.0 - kFullSuctionPa / 2, 100000.0, 100000.0,
                            100000.0, 100000.0, 100000.0, 100000.0};
  climbsim::DriveState drive;
  drive.wheels().resize(geometry.wheels.size());
  drive.wheels()[0].normal_force_n(500.0);
  climbsim::AdhesionForce force;
  force.downforce_n(2000.0);
  force.pf_x_m(0.01);
  const auto shapes = chamberShapes(geometry);
  const auto update = robotScene(geometry, shapes, &chambers, 100000.0, &drive, &force, 1'500'000'000);
  ASSERT_EQ(update.entities().size(), 1u);
  const auto& e = update.entities()[0];
  EXPECT_EQ(e.frame_id(), "robot");
  EXPECT_EQ(e.timestamp().sec(), 1u);
  EXPECT_EQ(e.timestamp().nsec(), 500'000'000u);
  ASSERT_EQ(e.triangles().size(), geometry.chambers.size());
  EXPECT_DOUBLE_EQ(e.triangles()[0].color().r(), 1.0);
  EXPECT_DOUBLE_EQ(e.triangles()[1].color().r(), 0.5);
  EXPECT_DOUBLE_EQ(e.triangles()[2].color().r(), 0.0);
  for (std::size_t k = 0; k < e.triangles().size(); ++k) {
    const auto& t = e.triangles()[k];
    ASSERT_GT(t.points().size(), 0u);
    EXPECT_EQ(t.points().size() % 3, 0u);
    // The triangles cover the chamber: their areas add up to its suction area, none inverted.
    double area_m2 = 0.0;
    for (std::size_t i = 0; i < t.points().size(); i += 3) {
      const auto& a = t.points()[i];
      const auto& b = t.points()[i + 1];
      const auto& c = t.points()[i + 2];
      const double twice = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      EXPECT_GE(twice, -1e-15);
      area_m2 += 0.5 * twice;
    }
    // The arcs sampled every 6 degrees instead of every one: a chord's sliver less.
    EXPECT_NEAR(area_m2, geometry.chambers[k].area_m2, 0.01 * geometry.chambers[k].area_m2) << k;
    EXPECT_LT(t.points().size(), 3u * 80u) << k << ": a viewer needs no finer arcs";
  }
  ASSERT_EQ(e.arrows().size(), geometry.wheels.size() + 1);
  EXPECT_NEAR(e.arrows()[0].shaft_length() + e.arrows()[0].head_length(), 500.0 * kWheelArrowMPerN, 1e-12);
  EXPECT_DOUBLE_EQ(e.arrows().back().pose().position().x(), 0.01);

  const auto bare = robotScene(geometry, shapes, nullptr, 0.0, nullptr, nullptr, 0);
  EXPECT_EQ(bare.entities()[0].arrows().size(), 0u);
}

TEST(FoxgloveScene, TheTransformIsTheRobotsPoseAndTheGridGoesUpAlongY) {
  climbsim::RobotState pose;
  pose.position_m() = {1.0, 2.0, 3.0};
  pose.orientation_wxyz() = {0.5, 0.5, -0.5, 0.5};
  const auto tf = robotTransform(pose, 0).transforms().at(0);
  EXPECT_EQ(tf.parent_frame_id(), "wall");
  EXPECT_EQ(tf.child_frame_id(), "robot");
  EXPECT_EQ(tf.translation().y(), 2.0);
  EXPECT_EQ(tf.rotation().w(), 0.5);
  EXPECT_EQ(tf.rotation().y(), -0.5);

  climbsim::DepthGrid grid;
  grid.size(2);
  grid.cell_m(0.1);
  grid.height_m() = {1.0f, 2.0f, 3.0f, 4.0f};  // row 0 (+y): 1 2; row 1: 3 4
  const auto g = depthGridMessage(grid);
  ASSERT_EQ(g.data().size(), 16u);
  float first = 0.0f;
  std::memcpy(&first, g.data().data(), sizeof first);
  EXPECT_EQ(first, 3.0f);
  EXPECT_DOUBLE_EQ(g.pose().position().x(), -0.1);
  EXPECT_EQ(g.fields().at(0).type(), foxglove::FLOAT32);
}

TEST(FoxgloveScene, AWholeDepthImageIsAGridCentredOnTheRobotGoingUpAlongY) {
  climbsim::DepthImage image;
  image.step(8);
  image.t_ns(40'000'000);
  image.width_px(4);
  image.height_px(4);
  image.pixel_size_m(0.2);
  image.tile_rows(4);
  image.tile_cols(4);
  image.height_m().assign(16, 0.002f);
  image.height_m()[0] = -0.01f;  // row 0 (+y), column 0 (-x)
  const auto grid = depthImageMessage(image);
  EXPECT_EQ(grid.column_count(), 4u);
  EXPECT_DOUBLE_EQ(grid.cell_size().x(), 0.2);
  EXPECT_DOUBLE_EQ(grid.pose().position().x(), -0.4);
  EXPECT_DOUBLE_EQ(grid.pose().position().y(), -0.4);
  ASSERT_EQ(grid.data().size(), 16u * sizeof(float));
  float first = 0.0f;
  std::memcpy(&first, grid.data().data() + 12 * sizeof(float), sizeof(float));  // the grid's top row, column 0
  EXPECT_EQ(first, -0.01f);
  EXPECT_EQ(grid.timestamp().sec(), 0u);
  EXPECT_EQ(grid.timestamp().nsec(), 40'000'000u);
}

TEST(FoxgloveScene, FoxglovesSchemasResolveFromTheVendoredFiles) {
  const std::string text = recording::omgidlSchemaText("foxglove::SceneUpdate");
  EXPECT_NE(text.find("struct SceneEntity {"), std::string::npos);
  EXPECT_NE(text.find("struct TriangleListPrimitive {"), std::string::npos);
  EXPECT_NE(text.find("enum SceneEntityDeletionType {"), std::string::npos);
  EXPECT_EQ(text.find("#include"), std::string::npos);
  EXPECT_LT(text.find("struct Point3 {"), text.find("struct TriangleListPrimitive {"));
}

}  // namespace
}  // namespace climbsim::recorder
