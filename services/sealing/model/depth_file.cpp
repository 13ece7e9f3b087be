#include "depth_file.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "climbsim/errors.hpp"

namespace climbsim::sealing {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

std::string cvTypeName(int type) {
  static const char* kDepths[] = {"8U", "8S", "16U", "16S", "32S", "32F", "64F", "16F"};
  return std::string(kDepths[CV_MAT_DEPTH(type)]) + "C" + std::to_string(CV_MAT_CN(type));
}

/// The value of `key` in a .npy header dict, up to the next top-level ',' or '}'.
std::string headerValue(const std::string& header, const std::string& key) {
  const std::string quoted = "'" + key + "'";
  const auto at = header.find(quoted);
  if (at == std::string::npos) throw std::invalid_argument("npy header has no " + quoted);
  auto pos = header.find(':', at + quoted.size());
  if (pos == std::string::npos) throw std::invalid_argument("npy header: no value for " + quoted);
  ++pos;
  while (pos < header.size() && header[pos] == ' ') ++pos;
  int depth = 0;
  std::string value;
  for (; pos < header.size(); ++pos) {
    const char ch = header[pos];
    if (ch == '(') ++depth;
    if (ch == ')') --depth;
    if (depth == 0 && (ch == ',' || ch == '}')) break;
    value += ch;
  }
  while (!value.empty() && value.back() == ' ') value.pop_back();
  return value;
}

}  // namespace

std::vector<float> parseNpyFloat32(const std::string& bytes, int& rows, int& cols) {
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) {
    throw std::invalid_argument("not a .npy file (no \\x93NUMPY magic)");
  }
  const auto major = static_cast<unsigned char>(bytes[6]);
  std::size_t header_len = 0;
  std::size_t header_start = 0;
  if (major == 1) {
    header_len = static_cast<unsigned char>(bytes[8]) | (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw std::invalid_argument("truncated .npy header");
    for (int b = 3; b >= 0; --b) header_len = (header_len << 8) | static_cast<unsigned char>(bytes[8 + b]);
    header_start = 12;
  } else {
    throw std::invalid_argument("unsupported .npy version " + std::to_string(major));
  }
  if (bytes.size() < header_start + header_len) throw std::invalid_argument("truncated .npy header");
  const std::string header = bytes.substr(header_start, header_len);
  const std::string descr = headerValue(header, "descr");
  if (descr != "'<f4'") throw std::invalid_argument("dtype " + descr + ", expected '<f4' (little-endian float32)");
  const std::string order = headerValue(header, "fortran_order");
  if (order != "False") throw std::invalid_argument("fortran_order " + order + ", expected False (C order)");
  const std::string shape = headerValue(header, "shape");
  long h = -1;
  long w = -1;
  char close = 0;
  char trailing = 0;
  if (std::sscanf(shape.c_str(), "(%ld, %ld%c%c", &h, &w, &close, &trailing) < 3 || close != ')' ||
      (trailing != 0) || h <= 0 || w <= 0 || h > 1 << 15 || w > 1 << 15) {
    throw std::invalid_argument("shape " + shape + ", expected (rows, cols) of a 2-D array");
  }
  const std::size_t data_start = header_start + header_len;
  const std::size_t count = static_cast<std::size_t>(h) * static_cast<std::size_t>(w);
  if (bytes.size() - data_start != count * sizeof(float)) {
    throw std::invalid_argument("holds " + std::to_string(bytes.size() - data_start) + " data bytes, shape " +
                                shape + " needs " + std::to_string(count * sizeof(float)));
  }
  std::vector<float> values(count);
  // Little-endian float32 on a little-endian host (every platform climbsim targets).
  std::memcpy(values.data(), bytes.data() + data_start, count * sizeof(float));
  rows = static_cast<int>(h);
  cols = static_cast<int>(w);
  return values;
}

DepthGrid readDepthFile(const std::string& path, const DepthFileOptions& options) {
  auto fail = [&](const std::string& problem) { return ConfigError(path + ": " + problem); };
  if (!std::filesystem::is_regular_file(path)) throw fail("cannot read it: no such file");
  if (!(options.view_m > 0.0) || !std::isfinite(options.view_m)) {
    std::ostringstream why;
    why << "--view-m = " << options.view_m << ": must be finite and > 0";
    throw fail(why.str());
  }
  const std::string ext = lowerExtension(path);
  const bool png = ext == ".png";
  if (options.scale_m_per_count && !png) throw fail("--scale applies to 16-bit PNG files only");

  DepthGrid depth;
  if (ext == ".npy") {
    std::ifstream in(path, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    if (!in) throw fail("cannot read it");
    try {
      depth.height_m = parseNpyFloat32(bytes.str(), depth.grid.height_px, depth.grid.width_px);
    } catch (const std::invalid_argument& e) {
      throw fail(e.what());
    }
  } else if (ext == ".tif" || ext == ".tiff" || png) {
    cv::Mat image;
    try {
      image = cv::imread(path, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception& e) {
      throw fail(std::string("cannot decode it: ") + e.what());
    }
    if (image.empty()) throw fail("cannot decode it as " + ext.substr(1));
    if (png) {
      if (image.type() != CV_16UC1) {
        throw fail("pixel type " + cvTypeName(image.type()) + ", expected a 16-bit one-channel PNG (16UC1)");
      }
      if (!options.scale_m_per_count) throw fail("a 16-bit PNG needs --scale M_PER_COUNT (and --height-offset-m M)");
      const double scale = *options.scale_m_per_count;
      if (!std::isfinite(scale) || scale == 0.0 || !std::isfinite(options.offset_m)) {
        throw fail("--scale and --height-offset-m must be finite, --scale != 0");
      }
      cv::Mat heights(image.rows, image.cols, CV_32FC1);
      for (int r = 0; r < image.rows; ++r) {
        for (int c = 0; c < image.cols; ++c) {
          heights.at<float>(r, c) = static_cast<float>(options.offset_m + scale * image.at<std::uint16_t>(r, c));
        }
      }
      image = heights;
    } else if (image.type() != CV_32FC1) {
      throw fail("pixel type " + cvTypeName(image.type()) + ", expected one channel of float32 (32FC1)");
    }
    depth.grid.height_px = image.rows;
    depth.grid.width_px = image.cols;
    depth.height_m.assign(image.begin<float>(), image.end<float>());
  } else {
    throw fail("unknown extension '" + ext + "' (expected .tif, .tiff, .png or .npy)");
  }
  depth.grid.pixel_size_m = options.view_m / depth.grid.width_px;
  for (std::size_t i = 0; i < depth.height_m.size(); ++i) {
    if (!std::isfinite(depth.height_m[i])) {
      std::ostringstream why;
      why << "pixel (row " << i / depth.grid.width_px << ", col " << i % depth.grid.width_px << ") is "
          << depth.height_m[i] << " (heights must be finite)";
      throw fail(why.str());
    }
  }
  return depth;
}

}  // namespace climbsim::sealing
