#include "depth_image_writer.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/errors.hpp"

namespace climbsim::scene {

namespace {

// Height as a fraction of [far, near], clamped to [0, 1].
double unitHeight(double h, const DepthImage& image) {
  return std::clamp((h - image.far_m) / (image.near_m - image.far_m), 0.0, 1.0);
}

void write(const cv::Mat& mat, const std::string& path) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, mat);
  } catch (const cv::Exception& e) {
    throw ConfigError("depth image '" + path + "': cannot write it: " + e.what());
  }
  if (!ok) throw ConfigError("depth image '" + path + "': cannot write it");
}

}  // namespace

cv::Mat depthTo16bit(const DepthImage& image) {
  cv::Mat out(image.height_px, image.width_px, CV_16UC1);
  for (int r = 0; r < image.height_px; ++r) {
    auto* row = out.ptr<std::uint16_t>(r);
    for (int c = 0; c < image.width_px; ++c) {
      row[c] = static_cast<std::uint16_t>(std::lround(unitHeight(image.at(r, c), image) * 65535.0));
    }
  }
  return out;
}

double heightFrom16bit(std::uint16_t count, double near_m, double far_m) {
  return far_m + count * (near_m - far_m) / 65535.0;
}

cv::Mat depthToColour(const DepthImage& image, int colormap) {
  cv::Mat grey(image.height_px, image.width_px, CV_8UC1);
  for (int r = 0; r < image.height_px; ++r) {
    auto* row = grey.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.width_px; ++c) {
      row[c] = static_cast<std::uint8_t>(std::lround(unitHeight(image.at(r, c), image) * 255.0));
    }
  }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, colormap);
  return colour;
}

void writeDepthPng16(const DepthImage& image, const std::string& path) { write(depthTo16bit(image), path); }

void writeDepthPngColour(const DepthImage& image, const std::string& path, int colormap) {
  write(depthToColour(image, colormap), path);
}

}  // namespace climbsim::scene
