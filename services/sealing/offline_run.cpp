#include "offline_run.hpp"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "sealing_model.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"
#include "sealing_pictures.hpp"

namespace climbsim::sealing {
namespace {

/// Grey scale of the pictures: the default camera's range [m].
constexpr double kPictureFar_m = -0.05;
constexpr double kPictureNear_m = 0.05;

void writePicture(const std::filesystem::path& path, const cv::Mat& picture) {
  bool ok = false;
  try {
    ok = cv::imwrite(path.string(), picture);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw ConfigError(path.string() + ": cannot write it");
}

}  // namespace

double runOffline(const OfflineOptions& options) {
  const RobotDescription robot = loadRobotDescription(options.robot_file);
  const RobotGeometry geometry = computeGeometry(robot);
  const DepthGrid depth = readDepthFile(options.depth_file, options.file);
  const SealingModel model(sealingParamsFromRobot(robot, geometry), geometry, depth.grid,
                           options.robot_file + " on " + options.depth_file);
  const SealingResult result = model.compute(depth);

  const std::filesystem::path out(options.out_dir);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out)) {
    throw ConfigError("--out = '" + options.out_dir + "': cannot create the directory (" + ec.message() + ")");
  }

  nlohmann::ordered_json json;
  json["depth_file"] = options.depth_file;
  json["robot_file"] = options.robot_file;
  json["robot"] = robot.name;
  json["width_px"] = depth.grid.width_px;
  json["height_px"] = depth.grid.height_px;
  json["pixel_size_m"] = depth.grid.pixel_size_m;
  json["max_slope"] = model.params().max_slope;
  json["travel_m"] = model.params().travel_m;
  json["basic_gap_m"] = model.params().basic_gap_m;
  json["kappa_L"] = model.params().kappa_L;
  double total_m2 = 0.0, basic_m2 = 0.0, gap_sum_m = 0.0;
  std::size_t pixels = 0, over = 0;
  const auto closed = model.closedLeaks();
  nlohmann::ordered_json segments = nlohmann::ordered_json::array();
  for (std::size_t s = 0; s < model.segmentCount(); ++s) {
    const SegmentLeak& leak = result.segments[s];
    nlohmann::ordered_json entry;
    entry["name"] = model.params().segment_names[s];
    entry["length_m"] = model.params().segment_length_m[s];
    entry["pixels"] = leak.pixels;
    entry["leak_area_m2"] = leak.leak_area_m2;
    entry["basic_leak_area_m2"] = closed[s].leak_area_m2;
    entry["mean_gap_m"] = leak.mean_gap_m;
    entry["max_gap_m"] = leak.max_gap_m;
    entry["over_travel_px"] = leak.over_travel_px;
    segments.push_back(entry);
    total_m2 += leak.leak_area_m2;
    basic_m2 += closed[s].leak_area_m2;
    gap_sum_m += leak.mean_gap_m * static_cast<double>(leak.pixels);
    pixels += leak.pixels;
    over += leak.over_travel_px;
  }
  json["segments"] = segments;
  json["total_leak_area_m2"] = total_m2;
  json["total_basic_leak_area_m2"] = basic_m2;
  json["mean_gap_m"] = gap_sum_m / static_cast<double>(pixels);
  json["over_travel_px"] = over;

  const auto json_path = out / "leakage.json";
  std::ofstream file(json_path);
  file << json.dump(2) << '\n';
  file.close();
  if (!file) throw ConfigError(json_path.string() + ": cannot write it");
  writePicture(out / "edges.png", edgesPicture(depth, model.masks(), kPictureFar_m, kPictureNear_m));
  writePicture(out / "gaps.png", gapsPicture(depth, model.masks(), result.sealing_m, model.params().travel_m,
                                             kPictureFar_m, kPictureNear_m));
  spdlog::info("sealing: {}: total leak area {:.6g} m^2 (closed sealing {:.6g} m^2), mean gap {:.6g} m -> {}",
               options.depth_file, total_m2, basic_m2, gap_sum_m / static_cast<double>(pixels), out.string());
  return total_m2;
}

}  // namespace climbsim::sealing
