#include "depth_camera.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::scene {

const char* toString(DepthBackend backend) {
  return backend == DepthBackend::kEmbree ? "embree" : "rasterizer";
}

namespace {

template <typename T>
[[noreturn]] void badValue(const char* key, T value, const char* requirement) {
  std::ostringstream msg;
  msg << "depth camera: " << key << " = " << value << ": " << requirement;
  throw ConfigError(msg.str());
}

}  // namespace

void DepthCameraParams::validate() const {
  if (width_px < 1 || width_px > kMaxDepthImageSidePx) badValue("width_px", width_px, "must be in 1..1024");
  if (height_px < 1 || height_px > kMaxDepthImageSidePx) badValue("height_px", height_px, "must be in 1..1024");
  if (!std::isfinite(pixel_size_m) || pixel_size_m <= 0.0) badValue("pixel_size_m", pixel_size_m, "must be > 0");
  if (!std::isfinite(near_m)) badValue("near_m", near_m, "must be finite");
  if (!std::isfinite(far_m)) badValue("far_m", far_m, "must be finite");
  if (!(near_m > far_m)) badValue("near_m", near_m, ("must be > far_m = " + std::to_string(far_m)).c_str());
  if (!tile.whole()) {
    if (tile.rows < 1 || tile.cols < 1) badValue("tile.rows", tile.rows < 1 ? tile.rows : tile.cols, "a tile needs >= 1 row and column");
    if (tile.row0 < 0 || tile.row0 + tile.rows > height_px) badValue("tile.row0", tile.row0, "the tile's rows must lie in the image");
    if (tile.col0 < 0 || tile.col0 + tile.cols > width_px) badValue("tile.col0", tile.col0, "the tile's columns must lie in the image");
  }
}

int quantisationLevel(double height_m, double near_m, double far_m) {
  const double k = std::floor((height_m - far_m) / quantisationStep_m(near_m, far_m));
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(kQuantisationLevels - 1)));
}

double quantisedHeight(int level, double near_m, double far_m) {
  return far_m + level * quantisationStep_m(near_m, far_m);
}

void quantise8bit(DepthImage& image) {
  for (float& h : image.height_m) {
    h = static_cast<float>(quantisedHeight(quantisationLevel(h, image.near_m, image.far_m), image.near_m, image.far_m));
  }
  image.quantised_8bit = true;
}

}  // namespace climbsim::scene
