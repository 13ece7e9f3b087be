// Depth image files for the offline mode: float32 TIFF, 16-bit PNG with scale and offset,
// .npy float32; every bad file is a ConfigError naming the file and the problem.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/errors.hpp"
#include "depth_file.hpp"

namespace climbsim::sealing::testing {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  const fs::path dir = fs::temp_directory_path() / ("climbsim-sealing-depth-file-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

/// A .npy file of `rows` x `cols` float32 values with the given header fields.
void writeNpy(const fs::path& path, int rows, int cols, const std::vector<float>& values,
              const std::string& descr = "<f4", const std::string& fortran = "False") {
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + fortran + ", 'shape': (" +
                       std::to_string(rows) + ", " + std::to_string(cols) + "), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const auto len = static_cast<std::uint16_t>(header.size());
  out.put(static_cast<char>(len & 0xff));
  out.put(static_cast<char>(len >> 8));
  out << header;
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
}

std::vector<float> ramp(int rows, int cols) {
  std::vector<float> v(static_cast<std::size_t>(rows) * cols);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>(1e-4 * (static_cast<double>(i % 97) - 48));
  return v;
}

/// Options of an image 0.8 m wide.
DepthFileOptions viewed() {
  DepthFileOptions options;
  options.view_m = 0.8;
  return options;
}

std::string errorOf(const std::string& path, const DepthFileOptions& options = viewed()) {
  try {
    readDepthFile(path, options);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DepthFile, Float32TiffRoundTrips) {
  const auto dir = tempDir();
  const auto values = ramp(30, 40);
  cv::Mat image(30, 40, CV_32FC1, const_cast<float*>(values.data()));
  ASSERT_TRUE(cv::imwrite((dir / "d.tif").string(), image));
  DepthFileOptions options;
  options.view_m = 0.4;
  const DepthGrid d = readDepthFile((dir / "d.tif").string(), options);
  EXPECT_EQ(d.grid.width_px, 40);
  EXPECT_EQ(d.grid.height_px, 30);
  EXPECT_DOUBLE_EQ(d.grid.pixel_size_m, 0.01);
  EXPECT_EQ(d.height_m, values);
}

TEST(DepthFile, SixteenBitPngIsScaledAndOffset) {
  const auto dir = tempDir();
  cv::Mat image(4, 5, CV_16UC1);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c) image.at<std::uint16_t>(r, c) = static_cast<std::uint16_t>(r * 10000 + c * 1000);
  ASSERT_TRUE(cv::imwrite((dir / "d.png").string(), image));
  DepthFileOptions options = viewed();
  options.scale_m_per_count = 1e-6;
  options.offset_m = -0.02;
  const DepthGrid d = readDepthFile((dir / "d.png").string(), options);
  ASSERT_EQ(d.height_m.size(), 20u);
  EXPECT_EQ(d.height_m[2 * 5 + 3], static_cast<float>(-0.02 + 1e-6 * 23000));
  EXPECT_NE(errorOf((dir / "d.png").string()).find("d.png: a 16-bit PNG needs --scale"), std::string::npos);
  cv::Mat eight(4, 5, CV_8UC1, cv::Scalar(3));
  ASSERT_TRUE(cv::imwrite((dir / "e.png").string(), eight));
  EXPECT_NE(errorOf((dir / "e.png").string(), options).find("e.png: pixel type 8UC1"), std::string::npos);
}

TEST(DepthFile, NpyFloat32RoundTrips) {
  const auto dir = tempDir();
  const auto values = ramp(7, 9);
  writeNpy(dir / "d.npy", 7, 9, values);
  const DepthGrid d = readDepthFile((dir / "d.npy").string(), viewed());
  EXPECT_EQ(d.grid.width_px, 9);
  EXPECT_EQ(d.grid.height_px, 7);
  EXPECT_EQ(d.height_m, values);
}

TEST(DepthFile, BadFilesNameTheFileAndTheProblem) {
  const auto dir = tempDir();
  const std::string missing = (dir / "missing.tif").string();
  EXPECT_EQ(errorOf(missing), missing + ": cannot read it: no such file");

  writeNpy(dir / "f8.npy", 2, 2, {0, 0, 0, 0, 0, 0, 0, 0}, "<f8");
  EXPECT_NE(errorOf((dir / "f8.npy").string()).find("f8.npy: dtype '<f8'"), std::string::npos);
  writeNpy(dir / "fortran.npy", 2, 2, {0, 0, 0, 0}, "<f4", "True");
  EXPECT_NE(errorOf((dir / "fortran.npy").string()).find("fortran_order True"), std::string::npos);
  writeNpy(dir / "short.npy", 3, 3, {0, 0, 0, 0});
  EXPECT_NE(errorOf((dir / "short.npy").string()).find("short.npy: holds 16 data bytes"), std::string::npos);
  { std::ofstream(dir / "junk.npy") << "hello"; }
  EXPECT_NE(errorOf((dir / "junk.npy").string()).find("junk.npy: not a .npy file"), std::string::npos);

  auto values = ramp(3, 3);
  values[4] = std::numeric_limits<float>::quiet_NaN();
  writeNpy(dir / "nan.npy", 3, 3, values);
  EXPECT_EQ(errorOf((dir / "nan.npy").string()),
            (dir / "nan.npy").string() + ": pixel (row 1, col 1) is nan (heights must be finite)");

  cv::Mat rgb(3, 3, CV_32FC3, cv::Scalar(0, 0, 0));
  ASSERT_TRUE(cv::imwrite((dir / "rgb.tif").string(), rgb));
  EXPECT_NE(errorOf((dir / "rgb.tif").string()).find("rgb.tif: pixel type 32FC3"), std::string::npos);
  { std::ofstream(dir / "broken.tif") << "not a tiff"; }
  EXPECT_NE(errorOf((dir / "broken.tif").string()).find("broken.tif: cannot decode it"), std::string::npos);
  { std::ofstream(dir / "d.jpg") << "x"; }
  EXPECT_NE(errorOf((dir / "d.jpg").string()).find("unknown extension '.jpg'"), std::string::npos);
  DepthFileOptions scaled = viewed();
  scaled.scale_m_per_count = 1e-6;
  EXPECT_NE(errorOf((dir / "rgb.tif").string(), scaled).find("--scale applies to 16-bit PNG files only"),
            std::string::npos);
}

}  // namespace
}  // namespace climbsim::sealing::testing
