#include "sealing_pictures.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::sealing {
namespace {

std::uint8_t toByte(double fraction) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(fraction, 0.0, 1.0)));
}

std::uint8_t depthGrey(float height_m, double far_m, double near_m) {
  return toByte((height_m - far_m) / (near_m - far_m));
}

}  // namespace

cv::Mat edgesPicture(const DepthGrid& depth, const StripMasks& masks, double far_m, double near_m) {
  const PixelGrid& g = depth.grid;
  cv::Mat picture(g.height_px, g.width_px, CV_8UC3);
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * g.width_px + c;
      const std::uint8_t grey = depthGrey(depth.height_m[i], far_m, near_m);
      cv::Vec3b colour(grey, grey, grey);
      const int segment = masks.segmentOfPixel(i);
      if (segment >= 0) {
        bool outline = false;
        bool border = false;
        static constexpr int kSteps[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
        for (const auto& d : kSteps) {
          const int nr = r + d[0];
          const int nc = c + d[1];
          if (nr < 0 || nr >= g.height_px || nc < 0 || nc >= g.width_px) {
            outline = true;
            continue;
          }
          const int other = masks.segmentOfPixel(static_cast<std::size_t>(nr) * g.width_px + nc);
          outline = outline || other < 0;
          border = border || (other >= 0 && other != segment);
        }
        if (outline) {
          colour = cv::Vec3b(0, 0, 255);
        } else if (border) {
          colour = cv::Vec3b(0, 255, 255);
        }
      }
      picture.at<cv::Vec3b>(r, c) = colour;
    }
  }
  return picture;
}

cv::Mat gapsPicture(const DepthGrid& depth, const StripMasks& masks, const std::vector<double>& sealing_m,
                    double full_scale_gap_m, double far_m, double near_m) {
  const PixelGrid& g = depth.grid;
  cv::Mat picture(g.height_px, g.width_px, CV_8UC3);
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * g.width_px + c;
      const std::int32_t k = masks.sealingIndexOfPixel(i);
      if (k >= 0) {
        // NaN: outside a shard's region (not computed), drawn as no gap.
        const std::uint8_t grey =
            std::isnan(sealing_m[k]) ? 0 : toByte((sealing_m[k] - depth.height_m[i]) / full_scale_gap_m);
        picture.at<cv::Vec3b>(r, c) = cv::Vec3b(grey, grey, grey);
      } else {
        const std::uint8_t grey = depthGrey(depth.height_m[i], far_m, near_m);
        picture.at<cv::Vec3b>(r, c) = cv::Vec3b(static_cast<std::uint8_t>(64 + grey / 2), 0, 0);
      }
    }
  }
  return picture;
}

}  // namespace climbsim::sealing
