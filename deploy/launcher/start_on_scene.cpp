#include "start_on_scene.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "climbsim/yaml_fields.hpp"

namespace climbsim::launcher {

namespace {
/// Spacing of the samples along a strip's centre line [m].
constexpr double kStripSample_m = 0.005;

std::string formatMetres(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", v);
  return text;
}

std::string formatValue(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}
}  // namespace

OffScene offSceneAt(const scene::WallCoverage& coverage, const RobotGeometry& geometry, double x_m, double y_m,
                    double yaw_rad) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  OffScene off;
  auto onWall = [&](const RobotGeometry::Point& p_R) {
    const double x = x_m + c * p_R.x_m - s * p_R.y_m;
    const double y = y_m + s * p_R.x_m + c * p_R.y_m;
    if (coverage.covered(x, y)) return true;
    off.beyond_x = off.beyond_x || coverage.empty() || x < coverage.minX() || x > coverage.maxX();
    off.beyond_y = off.beyond_y || coverage.empty() || y < coverage.minY() || y > coverage.maxY();
    return false;
  };
  for (std::size_t w = 0; w < geometry.wheels.size(); ++w) {
    if (!onWall(geometry.wheels[w].p_RobotWheel)) off.wheels.push_back(static_cast<int>(w) + 1);
  }
  for (const auto& segment : geometry.segments) {
    const auto& line = segment.centreline_Robot;
    std::size_t samples = 0, over_nothing = 0;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const double dx = line[k + 1].x_m - line[k].x_m, dy = line[k + 1].y_m - line[k].y_m;
      const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / kStripSample_m)));
      for (int i = 0; i < n; ++i) {  // the last point of the line follows below
        const double f = static_cast<double>(i) / n;
        ++samples;
        over_nothing += onWall({line[k].x_m + f * dx, line[k].y_m + f * dy}) ? 0 : 1;
      }
    }
    if (!line.empty()) {
      ++samples;
      over_nothing += onWall(line.back()) ? 0 : 1;
    }
    const double share = samples > 0 ? static_cast<double>(over_nothing) / static_cast<double>(samples) : 0.0;
    if (share >= kStartOverNothingShare) off.segments.emplace_back(segment.name, share);
  }
  return off;
}

std::string scenarioKeyWhere(const std::string& scenario_file, const std::vector<std::string>& overrides,
                             const std::string& key) {
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {
    if (it->substr(0, it->find('=')) == key) return scenario_file + " (--set " + YamlFields::shortText(*it) + ")";
  }
  try {
    const YAML::Node root = YAML::LoadFile(scenario_file);
    // Walks the dotted path without assigning nodes (yaml-cpp's assignment rebinds the tree).
    const std::function<int(const YAML::Node&, std::size_t)> lineAt = [&](const YAML::Node& node, std::size_t begin) {
      if (!node || !node.IsMap()) return -1;
      const std::size_t dot = key.find('.', begin);
      const YAML::Node child = node[key.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin)];
      if (!child) return -1;
      return dot == std::string::npos ? child.Mark().line : lineAt(child, dot + 1);
    };
    const int line = lineAt(root, 0);
    if (line >= 0) return scenario_file + ":" + std::to_string(line + 1);
  } catch (const std::exception&) {
  }
  return scenario_file;
}

std::optional<std::string> startOffSceneMessage(const OffScene& off, const scene::WallCoverage& coverage,
                                                double x_m, double y_m, double yaw_deg,
                                                const std::function<std::string(const std::string&)>& key_where,
                                                const std::string& scene_file) {
  if (!off.any()) return std::nullopt;
  // The key to change: the coordinate that lies beyond the scene's walls (both, or the pose,
  // for a hole inside them).
  std::string head;
  if (off.beyond_x && !off.beyond_y) {
    head = key_where("start.x_m") + ": start.x_m = " + formatValue(x_m);
  } else if (off.beyond_y && !off.beyond_x) {
    head = key_where("start.y_m") + ": start.y_m = " + formatValue(y_m);
  } else {
    head = key_where("start.x_m") + ": start = {x_m: " + formatValue(x_m) + ", y_m: " + formatValue(y_m) +
           ", yaw_deg: " + formatValue(yaw_deg) + "}";
  }
  std::string what;
  if (!off.wheels.empty()) {
    what = off.wheels.size() == 1 ? "wheel " : "wheels ";
    for (std::size_t i = 0; i < off.wheels.size(); ++i) what += (i ? ", " : "") + std::to_string(off.wheels[i]);
  }
  if (!off.segments.empty()) {
    // One short line: the first few by name, then how many more.
    constexpr std::size_t kNamed = 3;
    std::string segments;
    for (std::size_t i = 0; i < off.segments.size() && i < kNamed; ++i) {
      const auto& [name, share] = off.segments[i];
      segments += (segments.empty() ? "" : ", ") + name + " (" + std::to_string(std::lround(share * 100.0)) + " %)";
    }
    if (off.segments.size() > kNamed) segments += " and " + std::to_string(off.segments.size() - kNamed) + " more";
    what += (what.empty() ? "" : " and ") + std::string(off.segments.size() == 1 ? "strip " : "strips ") + segments;
  }
  std::string span = coverage.empty()
                         ? "no wall near the wall plane"
                         : "walls at x " + formatMetres(coverage.minX()) + ".." + formatMetres(coverage.maxX()) +
                               " m, y " + formatMetres(coverage.minY()) + ".." + formatMetres(coverage.maxY()) + " m";
  return head + ": the robot would start off the scene: " + what + " have no wall within " +
         formatValue(coverage.reach()) + " m under them (" +
         YamlFields::shortText(std::filesystem::path(scene_file).filename().string()) + ": " + span + ")";
}

}  // namespace climbsim::launcher
