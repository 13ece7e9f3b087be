#include "scene_translate.hpp"

#include <algorithm>
#include <utility>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "climbsim/scenario.hpp"

namespace climbsim::scene {

std::string checkRobotState(const climbsim::RobotState& state) {
  std::ostringstream reason;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(state.position_m()[i])) {
      reason << "RobotState from '" << state.source() << "' step " << state.step() << ": position_m[" << i
             << "] = " << state.position_m()[i];
      return reason.str();
    }
  }
  double norm2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double q = state.orientation_wxyz()[i];
    if (!std::isfinite(q)) {
      reason << "RobotState from '" << state.source() << "' step " << state.step() << ": orientation_wxyz[" << i
             << "] = " << q;
      return reason.str();
    }
    norm2 += q * q;
  }
  if (std::abs(std::sqrt(norm2) - 1.0) > 1e-3) {
    reason << "RobotState from '" << state.source() << "' step " << state.step()
           << ": orientation_wxyz has norm " << std::sqrt(norm2) << " (must be 1)";
    return reason.str();
  }
  return "";
}

Pose robotPoseFromIdl(const climbsim::RobotState& state) {
  const auto& q = state.orientation_wxyz();
  Pose T = Pose::Identity();
  T.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(state.position_m()[0], state.position_m()[1], state.position_m()[2]);
  return T;
}

climbsim::RobotState robotStateToIdl(const Pose& T_W_R) {
  climbsim::RobotState state;
  const Eigen::Quaterniond q(T_W_R.linear());
  state.position_m({T_W_R.translation().x(), T_W_R.translation().y(), T_W_R.translation().z()});
  state.orientation_wxyz({q.w(), q.x(), q.y(), q.z()});
  return state;
}

namespace {

/// Support heights a DepthImage can hold (idl/scene.idl).
constexpr std::size_t kMaxSupports = 262144;

/// depthImageToIdl without the pixels (checks them against the size, though).
climbsim::DepthImage depthImageHeaderToIdl(const DepthImage& image) {
  const PixelTile tile =
      image.tile.whole() ? PixelTile{0, 0, image.height_px, image.width_px} : image.tile;
  constexpr int kMax = Scenario::DepthCamera::kMaxSizePx;
  if (image.width_px > kMax || image.height_px > kMax || image.width_px < 0 || image.height_px < 0 ||
      image.height_m.size() != static_cast<std::size_t>(tile.rows) * static_cast<std::size_t>(tile.cols)) {
    throw std::invalid_argument("DepthImage: " + std::to_string(image.width_px) + " x " +
                                std::to_string(image.height_px) + " px with " + std::to_string(image.height_m.size()) +
                                " heights does not fit the topic (at most " + std::to_string(kMax) + " x " +
                                std::to_string(kMax) + ")");
  }
  climbsim::DepthImage sample;
  sample.width_px(static_cast<std::uint32_t>(image.width_px));
  sample.height_px(static_cast<std::uint32_t>(image.height_px));
  sample.pixel_size_m(image.pixel_size_m);
  sample.near_m(image.near_m);
  sample.far_m(image.far_m);
  sample.quantised_8bit(image.quantised_8bit);
  sample.headroom_m(image.headroom_m);
  sample.tile_row0(static_cast<std::uint32_t>(tile.row0));
  sample.tile_col0(static_cast<std::uint32_t>(tile.col0));
  sample.tile_rows(static_cast<std::uint32_t>(tile.rows));
  sample.tile_cols(static_cast<std::uint32_t>(tile.cols));
  if (image.support_px.size() != image.support_m.size() || image.support_px.size() > kMaxSupports) {
    throw std::invalid_argument("DepthImage: " + std::to_string(image.support_px.size()) + " support pixels with " +
                                std::to_string(image.support_m.size()) + " heights does not fit the topic (at most " +
                                std::to_string(kMaxSupports) + ")");
  }
  sample.support_px(image.support_px);
  sample.support_m(image.support_m);
  return sample;
}

/// Runs a DepthImage can hold (the bound of mask_runs is two values a run).
constexpr std::size_t kMaxMaskRuns = 262144 / 2;

/// For a masked tile, its mask's runs inside the tile with their pixels gathered from the
/// tile's box into `sample` (mask_runs, height_m); false (nothing set) for a tile without a
/// mask, or one whose runs would not fit the topic or hold nothing: then the box is sent.
bool putMaskedPixels(const DepthImage& image, climbsim::DepthImage& sample) {
  if (!image.tile.mask || image.tile.whole()) return false;
  const PixelTile& tile = image.tile;
  const int w = image.width_px;
  std::vector<std::uint32_t> runs;
  std::vector<float> heights;
  runs.reserve(2 * image.tile.mask->runs().size());
  heights.reserve(image.tile.mask->count());
  for (const PixelMask::Run& run : image.tile.mask->runs()) {
    const int row = static_cast<int>(run.raster / static_cast<std::uint32_t>(w));
    if (row < tile.row0 || row >= tile.row0 + tile.rows) continue;
    const int first = std::max(static_cast<int>(run.raster % static_cast<std::uint32_t>(w)), tile.col0);
    const int end = std::min(static_cast<int>(run.raster % static_cast<std::uint32_t>(w) + run.length), tile.col0 + tile.cols);
    if (first >= end) continue;
    runs.push_back(static_cast<std::uint32_t>(row * w + first));
    runs.push_back(static_cast<std::uint32_t>(end - first));
    const auto from = image.height_m.begin() + static_cast<std::ptrdiff_t>(row - tile.row0) * tile.cols + (first - tile.col0);
    heights.insert(heights.end(), from, from + (end - first));
  }
  if (runs.empty() || runs.size() / 2 > kMaxMaskRuns) return false;
  sample.mask_runs(std::move(runs));
  sample.height_m(std::move(heights));
  return true;
}

}  // namespace

climbsim::DepthImage depthImageToIdl(const DepthImage& image) {
  climbsim::DepthImage sample = depthImageHeaderToIdl(image);
  if (!putMaskedPixels(image, sample)) sample.height_m(image.height_m);
  return sample;
}

climbsim::DepthImage depthImageToIdl(DepthImage&& image) {
  climbsim::DepthImage sample = depthImageHeaderToIdl(image);
  if (!putMaskedPixels(image, sample)) sample.height_m(std::move(image.height_m));
  return sample;
}

DepthImage depthImageFromIdl(const climbsim::DepthImage& sample) {
  const bool whole = (sample.tile_rows() == 0 && sample.tile_cols() == 0) ||
                     (sample.tile_row0() == 0 && sample.tile_col0() == 0 && sample.tile_rows() == sample.height_px() &&
                      sample.tile_cols() == sample.width_px());
  if (!whole) {
    throw std::invalid_argument("DepthImage from '" + std::string(sample.source()) + "': a tile, not a whole image");
  }
  if (sample.height_m().size() != static_cast<std::size_t>(sample.width_px()) * sample.height_px()) {
    throw std::invalid_argument("DepthImage from '" + std::string(sample.source()) + "': " +
                                std::to_string(sample.width_px()) + " x " + std::to_string(sample.height_px()) +
                                " px but " + std::to_string(sample.height_m().size()) + " heights");
  }
  DepthImage image;
  image.width_px = static_cast<int>(sample.width_px());
  image.height_px = static_cast<int>(sample.height_px());
  image.pixel_size_m = sample.pixel_size_m();
  image.near_m = sample.near_m();
  image.far_m = sample.far_m();
  image.quantised_8bit = sample.quantised_8bit();
  image.headroom_m = sample.headroom_m();
  image.height_m = sample.height_m();
  image.support_px = sample.support_px();
  image.support_m = sample.support_m();
  return image;
}

climbsim::DepthGrid depthGridToIdl(const HeightGrid& grid) {
  if (grid.size < 1 || grid.size > 64 || grid.height_m.size() != static_cast<std::size_t>(grid.size) * grid.size) {
    throw std::invalid_argument("DepthGrid: " + std::to_string(grid.size) + " cells per side with " +
                                std::to_string(grid.height_m.size()) + " heights does not fit the topic (at most 64)");
  }
  climbsim::DepthGrid sample;
  sample.size(static_cast<std::uint32_t>(grid.size));
  sample.cell_m(grid.cell_m);
  sample.height_m(grid.height_m);
  return sample;
}

climbsim::LaserScan laserScanToIdl(const LaserScan& scan, const Pose& T_W_S) {
  if (scan.ranges_m.size() > 4096) {
    throw std::invalid_argument("LaserScan: " + std::to_string(scan.ranges_m.size()) +
                                " beams do not fit the topic (at most 4096)");
  }
  climbsim::LaserScan sample;
  sample.angle_min_rad(scan.angle_min_rad);
  sample.angle_increment_rad(scan.angle_increment_rad);
  sample.range_max_m(scan.range_max_m);
  const Eigen::Quaterniond q(T_W_S.linear());
  sample.position_m({T_W_S.translation().x(), T_W_S.translation().y(), T_W_S.translation().z()});
  sample.orientation_wxyz({q.w(), q.x(), q.y(), q.z()});
  sample.ranges_m(scan.ranges_m);
  return sample;
}

std::optional<climbsim::DepthGrid> DepthGridSchedule::offer(const DepthImage& image, std::int64_t t_ns) {
  if (t_ns < next_ns_ || !image.tile.whole()) return std::nullopt;
  next_ns_ = (t_ns / kInterval_ns + 1) * kInterval_ns;
  return depthGridToIdl(downsampleHeights(image.height_m, static_cast<std::uint32_t>(image.width_px),
                                          static_cast<std::uint32_t>(image.height_px), image.pixel_size_m,
                                          blockFor(static_cast<std::uint32_t>(image.width_px), kCells)));
}

}  // namespace climbsim::scene
