// Debug images of depth images: the 16-bit PNG decodes back to the heights.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/errors.hpp"
#include "depth_image_writer.hpp"

namespace climbsim::scene {
namespace {

DepthImage ramp() {
  DepthImage image;
  image.width_px = 40;
  image.height_px = 30;
  image.pixel_size_m = 0.01;
  image.near_m = 0.05;
  image.far_m = -0.05;
  for (int r = 0; r < image.height_px; ++r) {
    for (int c = 0; c < image.width_px; ++c) {
      image.height_m.push_back(static_cast<float>(-0.05 + 0.1 * (r * image.width_px + c) / 1199.0));
    }
  }
  return image;
}

std::filesystem::path tempDir() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("climbsim_depth_writer_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(DepthImageWriter, SixteenBitPngDecodesToTheHeights) {
  const DepthImage image = ramp();
  const auto dir = tempDir();
  const std::string path = (dir / "depth16.png").string();
  writeDepthPng16(image, path);
  const cv::Mat back = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(back.type(), CV_16UC1);
  ASSERT_EQ(back.rows, image.height_px);
  ASSERT_EQ(back.cols, image.width_px);
  const double half_count = 0.1 / 65535.0 / 2.0;
  for (int r = 0; r < back.rows; ++r) {
    for (int c = 0; c < back.cols; ++c) {
      EXPECT_NEAR(heightFrom16bit(back.at<std::uint16_t>(r, c), image.near_m, image.far_m), image.at(r, c),
                  half_count + 1e-8);
    }
  }
  EXPECT_EQ(back.at<std::uint16_t>(0, 0), 0);          // far
  EXPECT_EQ(back.at<std::uint16_t>(29, 39), 65535);    // near
  std::filesystem::remove_all(dir);
}

TEST(DepthImageWriter, ColourPngFollowsTheColormap) {
  const DepthImage image = ramp();
  const auto dir = tempDir();
  const std::string path = (dir / "depth.png").string();
  writeDepthPngColour(image, path);
  const cv::Mat back = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(back.type(), CV_8UC3);
  cv::Mat lut_in(1, 2, CV_8UC1);
  lut_in.at<std::uint8_t>(0, 0) = 0;
  lut_in.at<std::uint8_t>(0, 1) = 255;
  cv::Mat lut_out;
  cv::applyColorMap(lut_in, lut_out, cv::COLORMAP_TURBO);
  EXPECT_EQ(back.at<cv::Vec3b>(0, 0), lut_out.at<cv::Vec3b>(0, 0));
  EXPECT_EQ(back.at<cv::Vec3b>(29, 39), lut_out.at<cv::Vec3b>(0, 1));
  EXPECT_NE(back.at<cv::Vec3b>(0, 0), back.at<cv::Vec3b>(29, 39));
  std::filesystem::remove_all(dir);
}

TEST(DepthImageWriter, UnwritablePathNamesThePath) {
  try {
    writeDepthPng16(ramp(), "/nonexistent-dir/x/depth.png");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x/depth.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace climbsim::scene
