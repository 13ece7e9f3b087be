#include "sealing_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace climbsim::plot {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kPi = 3.14159265358979323846;
const cv::Scalar kBlack(0, 0, 0), kWhite(255, 255, 255), kFrame(160, 160, 160);
constexpr int kView = 600;    ///< side of the wall-up view [px]
constexpr int kLegendW = 300; ///< legend column right of the view [px]
constexpr int kTitleH = 40;
constexpr int kFootH = 30;

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = 0.5, int thick = 1) {
  cv::putText(img, s, at, kFont, scale, kBlack, thick, cv::LINE_AA);
}

std::string fmt(const char* format, double v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

/// A vertical bar from `top` (colour at 1) to `bottom` (colour at 0) with end labels.
void colourBar(cv::Mat& img, cv::Rect bar, cv::Vec3b (*colour)(double), const std::string& lo, const std::string& hi) {
  for (int y = 0; y < bar.height; ++y) {
    const double f = 1.0 - static_cast<double>(y) / std::max(1, bar.height - 1);
    const cv::Vec3b c = colour(f);
    cv::line(img, cv::Point(bar.x, bar.y + y), cv::Point(bar.x + bar.width - 1, bar.y + y), cv::Scalar(c[0], c[1], c[2]));
  }
  cv::rectangle(img, bar, kFrame, 1);
  text(img, hi, cv::Point(bar.x + bar.width + 8, bar.y + 10), 0.45);
  text(img, lo, cv::Point(bar.x + bar.width + 8, bar.y + bar.height), 0.45);
}

cv::Vec3b grey(double f) {
  const auto g = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(f, 0.0, 1.0)));
  return {g, g, g};
}

cv::Vec3b navy(double f) {
  const auto g = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(f, 0.0, 1.0)));
  return {static_cast<std::uint8_t>(64 + g / 2), 0, 0};
}

void swatch(cv::Mat& img, cv::Point at, cv::Scalar colour, const std::string& label) {
  cv::rectangle(img, cv::Rect(at.x, at.y - 11, 22, 14), colour, cv::FILLED);
  cv::rectangle(img, cv::Rect(at.x, at.y - 11, 22, 14), kFrame, 1);
  text(img, label, cv::Point(at.x + 30, at.y), 0.45);
}

}  // namespace

cv::Mat annotateSealingPicture(const cv::Mat& raw, const SealingPictureInfo& info) {
  cv::Mat img(kTitleH + kView + kFootH, kView + kLegendW, CV_8UC3, kWhite);
  const double side = std::max(raw.cols, raw.rows);
  // The turned picture's bounding box fits the view.
  const double turned = side * (std::abs(std::cos(info.yaw_rad)) + std::abs(std::sin(info.yaw_rad)));
  const double scale = (kView - 20) / turned;
  const double yaw_deg = info.yaw_rad * 180.0 / kPi;
  // Robot frame (x right, y up in the raw picture) turned by the yaw: up in the view is up the
  // wall, as in the ring pictures. Nearest neighbour: every pixel keeps its exact colour.
  cv::Mat rotation = cv::getRotationMatrix2D(cv::Point2f(raw.cols / 2.0f, raw.rows / 2.0f), yaw_deg, scale);
  rotation.at<double>(0, 2) += kView / 2.0 - raw.cols / 2.0;
  rotation.at<double>(1, 2) += kTitleH + kView / 2.0 - raw.rows / 2.0;
  cv::warpAffine(raw, img, rotation, img.size(), cv::INTER_NEAREST, cv::BORDER_TRANSPARENT);
  const cv::Rect view(0, kTitleH, kView, kView);
  cv::rectangle(img, view, kFrame, 1);

  const std::string what = info.kind == "gaps" ? "Sealing gaps" : "Sealing strips on the depth image";
  text(img, what + fmt(" at t = %.3g s", info.t_s), cv::Point(12, 27), 0.7, 2);

  // The robot's x axis from the centre, like the ring pictures' white arrow (here red-framed black).
  const cv::Point2d centre(kView / 2.0, kTitleH + kView / 2.0);
  const double arrow_px = 0.08 / info.pixel_size_m * scale;
  const cv::Point2d tip = centre + arrow_px * cv::Point2d(std::cos(info.yaw_rad), -std::sin(info.yaw_rad));
  cv::arrowedLine(img, centre, tip, kWhite, 4, cv::LINE_AA, 0, 0.3);
  cv::arrowedLine(img, centre, tip, cv::Scalar(255, 0, 255), 2, cv::LINE_AA, 0, 0.3);

  // Scale bar: 10 cm on the wall.
  const double bar_m = 0.1;
  const int bar_px = static_cast<int>(std::lround(bar_m / info.pixel_size_m * scale));
  const cv::Point b0(16, kTitleH + kView - 18), b1(16 + bar_px, kTitleH + kView - 18);
  cv::rectangle(img, cv::Rect(b0.x - 6, b0.y - 22, bar_px + 12, 32), kWhite, cv::FILLED);
  cv::line(img, b0, b1, kBlack, 3);
  cv::line(img, b0 + cv::Point(0, -6), b0 + cv::Point(0, 6), kBlack, 2);
  cv::line(img, b1 + cv::Point(0, -6), b1 + cv::Point(0, 6), kBlack, 2);
  text(img, "10 cm", cv::Point(b0.x + bar_px / 2 - 22, b0.y - 8), 0.45);

  // Legend.
  const int lx = kView + 20;
  int y = kTitleH + 20;
  text(img, "up = up the wall", cv::Point(lx, y));
  y += 22;
  cv::arrowedLine(img, cv::Point(lx, y - 5), cv::Point(lx + 26, y - 5), cv::Scalar(255, 0, 255), 2, cv::LINE_AA, 0, 0.3);
  text(img, "robot x", cv::Point(lx + 34, y), 0.45);
  y += 30;
  if (info.kind == "gaps") {
    text(img, "gap of each sealing pixel", cv::Point(lx, y));
    text(img, "(sealing - wall):", cv::Point(lx, y + 18));
    colourBar(img, cv::Rect(lx, y + 32, 22, 160), grey, "0 mm (tight)",
              fmt(">= %.3g mm (open)", info.full_scale_gap_m * 1e3));
    y += 32 + 160 + 40;
    text(img, "outside the sealing: the wall's", cv::Point(lx, y));
    text(img, "height, dimmed in blue:", cv::Point(lx, y + 18));
    colourBar(img, cv::Rect(lx, y + 32, 22, 120), navy, fmt("%+.0f mm", info.far_m * 1e3), fmt("%+.0f mm", info.near_m * 1e3));
  } else {
    text(img, "height of the wall above the", cv::Point(lx, y));
    text(img, "sealing plane:", cv::Point(lx, y + 18));
    colourBar(img, cv::Rect(lx, y + 32, 22, 200), grey, fmt("%+.0f mm", info.far_m * 1e3), fmt("%+.0f mm", info.near_m * 1e3));
    y += 32 + 200 + 40;
    swatch(img, cv::Point(lx, y), cv::Scalar(0, 0, 255), "outline of the sealing strips");
    swatch(img, cv::Point(lx, y + 24), cv::Scalar(0, 255, 255), "border between segments");
  }
  text(img, fmt("1 px = %.2g mm on the wall", info.pixel_size_m * 1e3), cv::Point(12, kTitleH + kView + 21), 0.45);
  return img;
}

}  // namespace climbsim::plot
