#include "run_plots.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <limits>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/robot/depth_view.hpp"
#include "line_chart.hpp"
#include "picture_names.hpp"
#include "sealing_picture.hpp"

namespace climbsim::plot {
namespace {

/// The smallest y range of the P_F panels [mm]: a P_F that stays put is drawn on +-1 mm.
constexpr double kPfMinSpan_mm = 2.0;

std::vector<double> scaled(const std::vector<double>& v, double factor) {
  std::vector<double> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [&](double d) { return d * factor; });
  return out;
}

Series series(const TraceTable& trace, const std::string& column, const std::string& label, int colour,
              double factor = 1.0) {
  return Series{label, trace.column("t_s"), scaled(trace.column(column), factor), paletteColour(colour), false};
}

Series constant(const TraceTable& trace, double value, const std::string& label, cv::Scalar colour) {
  const auto& t = trace.column("t_s");
  Series s{label, {}, {}, colour, true};
  if (!t.empty()) {
    s.x = {t.front(), t.back()};
    s.y = {value, value};
  }
  return s;
}

void write(const std::string& path, const cv::Mat& img, std::vector<std::string>& written) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, img);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw ConfigError(path + ": cannot write the PNG");
  written.push_back(path);
}

}  // namespace

cv::Mat downforcePlot(const TraceTable& trace, double setpoint_n, const std::string& setpoint_label,
                      double hold_n, const std::vector<Marker>& marks) {
  ChartSpec spec;
  spec.markers = marks;
  spec.title = "Downforce F and its point of action P_F";
  Panel f{"F [N]", {series(trace, "downforce_n", "F", 0)}, 380};
  if (Series published = publishedSetpoint(trace); !published.x.empty()) {
    f.series.push_back(std::move(published));
  } else if (std::isfinite(setpoint_n) && setpoint_n > 0.0) {
    f.series.push_back(constant(trace, setpoint_n, setpoint_label, paletteColour(3)));
  } else if (!setpoint_label.empty()) {
    spec.title += " (" + setpoint_label + ")";  // no line: say why there is none
  }
  if (std::isfinite(hold_n) && hold_n > 0.0) {
    char label[64];
    std::snprintf(label, sizeof label, "m g / mu = %.0f N", hold_n);
    f.series.push_back(constant(trace, hold_n, label, cv::Scalar(90, 90, 90)));
  }
  // x and y in panels of their own: equal values would hide one under the other. P_F stays
  // at the centre without a vacuum: at least +-1 mm shown, not +-1e-9.
  Panel pf_x{"P_F x in R [mm]", {series(trace, "pf_x_m", "P_F x", 1, 1e3)}, 200, kPfMinSpan_mm};
  Panel pf_y{"P_F y in R [mm]", {series(trace, "pf_y_m", "P_F y", 2, 1e3)}, 200, kPfMinSpan_mm};
  spec.panels = {f, pf_x, pf_y};
  return drawChart(spec);
}

cv::Mat pressuresPlot(const TraceTable& trace, int chamber_count, int centre_chamber, bool has_reservoir,
                      double ambient_pa, const std::vector<Marker>& marks) {
  ChartSpec spec;
  spec.markers = marks;
  spec.title = (chamber_count == 1 ? std::string("Chamber pressure p1")
                                   : "Chamber pressures p1..p" + std::to_string(chamber_count)) +
               (has_reservoir ? " and reservoir p_R (absolute)" : " (absolute)");
  spec.panel_height_px = 130;
  spec.shared_y = true;
  // Small multiples: one panel per volume on one scale, none hidden under another.
  for (int i = 1; i <= chamber_count; ++i) {
    const std::string name = "p" + std::to_string(i);
    Panel p{name + " [kPa]", {series(trace, name + "_pa", i == centre_chamber ? name + " (centre)" : name, i - 1, 1e-3),
                              constant(trace, ambient_pa * 1e-3, "ambient", cv::Scalar(150, 150, 150))}};
    spec.panels.push_back(p);
  }
  if (has_reservoir) {
    Panel r{"p_R [kPa]", {series(trace, "pr_pa", "p_R (reservoir)", chamber_count, 1e-3),
                          constant(trace, ambient_pa * 1e-3, "ambient", cv::Scalar(150, 150, 150))}};
    r.series.front().colour = cv::Scalar(0, 0, 0);
    spec.panels.push_back(r);
  }
  return drawChart(spec);
}

cv::Mat valvesPlot(const TraceTable& trace, int valve_count, const std::vector<Marker>& marks) {
  ChartSpec spec;
  spec.markers = marks;
  spec.title = "Valve openings (0 closed .. 1 open)";
  spec.panel_height_px = 120;
  spec.shared_y = true;
  for (int i = 1; i <= valve_count; ++i) {
    Panel v{"valve " + std::to_string(i), {series(trace, "valve" + std::to_string(i), "valve " + std::to_string(i), i - 1)}};
    v.y_include = {0.0, 1.0};  // closed valves (no controller) still on the 0..1 scale
    spec.panels.push_back(v);
  }
  return drawChart(spec);
}

cv::Mat wheelLoadsPlot(const TraceTable& trace, int wheel_count, const std::vector<Marker>& marks) {
  ChartSpec loads;
  loads.markers = marks;
  loads.title = "Wheel normal loads and slip";
  loads.panel_height_px = 150;
  loads.shared_y = true;
  ChartSpec slips = loads;
  for (int i = 1; i <= wheel_count; ++i) {
    const std::string w = "wheel" + std::to_string(i);
    loads.panels.push_back(Panel{"load [N]", {series(trace, w + "_normal_n", "wheel " + std::to_string(i), i - 1)}});
    slips.panels.push_back(Panel{"slip [m/s]", {series(trace, w + "_slip_mps", "wheel " + std::to_string(i), i - 1)}});
  }
  // Loads on one scale, slips on another: two charts stacked into one picture.
  slips.title.clear();
  cv::Mat top = drawChart(loads), bottom = drawChart(slips), out;
  // The second chart has no title band: cut it.
  constexpr int kTitleBand = 44;
  cv::vconcat(top, bottom(cv::Rect(0, kTitleBand, bottom.cols, bottom.rows - kTitleBand)), out);
  return out;
}

RingScales ringScales(const TraceTable& trace, int chamber_count, int wheel_count, double ambient_pa) {
  RingScales s;
  double lo = std::numeric_limits<double>::infinity(), hi = ambient_pa;
  for (int i = 1; i <= chamber_count; ++i) {
    for (double p : trace.column("p" + std::to_string(i) + "_pa")) {
      if (std::isfinite(p)) {
        lo = std::min(lo, p);
        hi = std::max(hi, p);
      }
    }
  }
  if (!std::isfinite(lo) || hi - lo < 100.0) lo = hi - 100.0;  // at least 0.1 kPa of scale
  s.p_lo_pa = lo;
  s.p_hi_pa = hi;
  double load = 0.0;
  for (int i = 1; i <= wheel_count; ++i) {
    for (double f : trace.column("wheel" + std::to_string(i) + "_normal_n")) {
      if (std::isfinite(f)) load = std::max(load, f);
    }
  }
  s.load_max_n = load > 0.0 ? load : 1.0;
  return s;
}

RingMoment ringMoment(const TraceTable& trace, std::size_t row, int chamber_count, int wheel_count) {
  RingMoment m;
  m.t_s = trace.column("t_s").at(row);
  for (int i = 1; i <= chamber_count; ++i) m.chamber_pa.push_back(trace.column("p" + std::to_string(i) + "_pa").at(row));
  m.reservoir_pa = trace.has("pr_pa") ? trace.column("pr_pa").at(row) : std::nan("");
  for (int i = 1; i <= wheel_count; ++i) {
    m.wheel_normal_n.push_back(trace.column("wheel" + std::to_string(i) + "_normal_n").at(row));
  }
  m.pf_x_m = trace.column("pf_x_m").at(row);
  m.pf_y_m = trace.column("pf_y_m").at(row);
  m.downforce_n = trace.column("downforce_n").at(row);
  m.yaw_rad = trace.column("yaw_rad").at(row);
  if (!std::isfinite(m.yaw_rad)) m.yaw_rad = 0.0;
  return m;
}

Series publishedSetpoint(const TraceTable& trace) {
  Series s{"set-point (the controller's)", {}, {}, paletteColour(3), true};
  if (!trace.has("downforce_setpoint_n")) return s;  // a trace of an older recorder
  const auto& t = trace.column("t_s");
  const auto& v = trace.column("downforce_setpoint_n");
  bool any = false;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const bool stated = std::isfinite(v[k]) && v[k] > 0.0;
    any = any || stated;
    s.x.push_back(t[k]);
    s.y.push_back(stated ? v[k] : std::nan(""));  // a gap where none was stated
  }
  if (!any) {
    s.x.clear();
    s.y.clear();
  }
  return s;
}

Setpoint downforceSetpoint(const Scenario& scenario, const RobotDescription& robot) {
  switch (scenario.controller.kind) {
    case Scenario::ControllerKind::kReference: {
      const double f = scenario.controller.downforce_n > 0.0 ? scenario.controller.downforce_n
                                                             : robot.adhesion.desired_downforce_n;
      return {f, "set-point"};
    }
    case Scenario::ControllerKind::kNone: return {std::nan(""), "controller: none, no set-point"};
    case Scenario::ControllerKind::kFixed: return {std::nan(""), "controller: fixed valves, no set-point"};
    case Scenario::ControllerKind::kRecorded: return {std::nan(""), "controller: recorded commands"};
    case Scenario::ControllerKind::kExternal: break;
  }
  // An external controller that published none: the robot's, as what it was meant to hold.
  return {robot.adhesion.desired_downforce_n, "robot's desired F (the external controller published no set-point)"};
}

static double depthPixelSize(const std::string& scene_file, int width_px, const RobotDescription& robot) {
  // The depth camera of the scene's top file: size="w [h]" [m] across the image; without it the
  // scene service's default, the robot's view.
  std::ifstream in(scene_file);
  std::stringstream text;
  text << in.rdbuf();
  const std::string xml = text.str();
  const double robot_view_m = robotDepthViewM(computeGeometry(robot));
  double size_m = robot_view_m;
  std::smatch camera;
  if (std::regex_search(xml, camera, std::regex("<camera[^>]*>"))) {
    const std::string tag = camera.str();
    std::smatch m;
    if (std::regex_search(tag, m, std::regex("\\bsize=\"\\s*([0-9.eE+-]+)"))) size_m = std::strtod(m.str(1).c_str(), nullptr);
  }
  // The picture is the depth image's pixel grid, which covers the camera's size.
  return (size_m > 0.0 ? size_m : robot_view_m) / std::max(1, width_px);
}

static void writeSealingPictures(const std::string& run_dir, const std::string& out_dir, const Scenario& scenario,
                          const RobotDescription& robot, const TraceTable& trace, std::vector<std::string>& written) {
  namespace fs = std::filesystem;
  for (double t_req : scenario.pictures.sealing_at_s) {
    for (const char* kind : {"edges", "gaps"}) {
      const fs::path raw_file = fs::path(run_dir) / "pictures" / sealingPictureName(kind, t_req);
      if (!fs::exists(raw_file)) continue;  // the run ended before it, or the recorder kept none
      const cv::Mat raw = cv::imread(raw_file.string(), cv::IMREAD_COLOR);
      if (raw.empty()) {
        spdlog::warn("{}: not a PNG picture; skipped", raw_file.string());
        continue;
      }
      SealingPictureInfo info;
      info.kind = kind;
      info.t_s = t_req;
      info.yaw_rad = trace.column("yaw_rad").at(trace.rowNearest(t_req));
      if (!std::isfinite(info.yaw_rad)) info.yaw_rad = 0.0;
      info.pixel_size_m = depthPixelSize(scenario.scenePath(fs::path(run_dir).string()), raw.cols, robot);
      info.full_scale_gap_m = robot.sealing.travel_m;
      write((fs::path(out_dir) / sealingPictureName(kind, t_req)).string(), annotateSealingPicture(raw, info), written);
    }
  }
}

std::vector<Marker> runMarkers(const Scenario& scenario, const std::string& run_dir) {
  std::vector<Marker> marks;
  if (scenario.start.hold_s > 0.0) marks.push_back({scenario.start.hold_s, "released", cv::Scalar(170, 0, 170)});  // magenta
  std::ifstream in((std::filesystem::path(run_dir) / "summary.json").string());
  const auto summary = nlohmann::json::parse(in, nullptr, false);
  if (!summary.is_discarded() && summary.is_object() && summary.contains("fell_at_s") &&
      summary["fell_at_s"].is_number()) {
    marks.push_back({summary["fell_at_s"].get<double>(), "FELL", cv::Scalar(0, 0, 220)});
  }
  return marks;
}

double holdingDownforce(const Scenario& scenario, const RobotDescription& robot) {
  constexpr double kG = 9.81;
  constexpr double kPi = 3.14159265358979323846;
  const double weight_n = robot.body.mass_kg * kG;
  const double mu = robot.wheels.front().friction_coefficient;
  switch (scenario.wall.kind) {
    case Scenario::WallKind::kVertical:
      return weight_n / mu;  // friction must carry the whole weight
    case Scenario::WallKind::kOverhang: {
      // Past vertical by a: friction carries m g cos(a), the downforce also carries m g sin(a).
      const double a = scenario.wall.overhang_deg * kPi / 180.0;
      return weight_n * std::cos(a) / mu + weight_n * std::sin(a);
    }
    case Scenario::WallKind::kFloor:
      return 0.0;
  }
  return 0.0;
}

std::vector<std::string> writeRunPlots(const std::string& run_dir, const std::string& out_dir) {
  namespace fs = std::filesystem;
  const TraceTable trace = TraceTable::read((fs::path(run_dir) / "trace.csv").string());
  const Scenario scenario = loadScenario((fs::path(run_dir) / "scenario.yaml").string());
  const RobotDescription robot = loadRobotDescription(scenario.robotPath());
  const RobotGeometry geometry = computeGeometry(robot);
  const int chambers = static_cast<int>(geometry.chambers.size());
  const int wheels = static_cast<int>(geometry.wheels.size());
  const double ambient = robot.gas.ambient_pressure_pa;
  // Every column the plots read, checked before anything is drawn.
  const bool reservoir = geometry.has_reservoir;  // pr_pa and valve1..N only then
  std::vector<std::string> needed = {"t_s", "downforce_n", "pf_x_m", "pf_y_m", "yaw_rad"};
  if (reservoir) needed.push_back("pr_pa");
  for (int i = 1; i <= chambers; ++i) {
    needed.push_back("p" + std::to_string(i) + "_pa");
    if (reservoir) needed.push_back("valve" + std::to_string(i));
  }
  for (int i = 1; i <= wheels; ++i) {
    needed.push_back("wheel" + std::to_string(i) + "_normal_n");
    needed.push_back("wheel" + std::to_string(i) + "_slip_mps");
  }
  for (const auto& c : needed) trace.column(c);
  if (trace.rows() == 0) throw ConfigError(trace.source() + ": no rows (the run recorded no step)");

  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw ConfigError(out_dir + ": cannot create the plot directory (" + ec.message() + ")");
  std::vector<std::string> written;
  auto at = [&](const std::string& name) { return (fs::path(out_dir) / name).string(); };
  const Setpoint sp = downforceSetpoint(scenario, robot);
  const std::vector<Marker> marks = runMarkers(scenario, run_dir);
  write(at("downforce.png"), downforcePlot(trace, sp.downforce_n, sp.label, holdingDownforce(scenario, robot), marks),
        written);
  int centre = 0;  // a ring's centre disc (the last chamber)
  for (const auto& c : geometry.chambers) {
    if (chambers > 1 && c.inner_radius_m == 0.0 && c.outer_radius_m > 0.0) centre = c.number;
  }
  write(at("pressures.png"), pressuresPlot(trace, chambers, centre, reservoir, ambient, marks), written);
  if (reservoir) write(at("valves.png"), valvesPlot(trace, chambers, marks), written);
  write(at("wheel_loads.png"), wheelLoadsPlot(trace, wheels, marks), written);

  writeSealingPictures(run_dir, out_dir, scenario, robot, trace, written);

  const RingScales scales = ringScales(trace, chambers, wheels, ambient);
  const auto& t = trace.column("t_s");
  const double step = t.size() > 1 ? t[1] - t[0] : 0.0;
  for (double t_req : scenario.pictures.ring_at_s) {
    if (t_req < t.front() - step || t_req > t.back() + step) {
      spdlog::warn("{}: ring picture at {} s skipped: the trace covers {} .. {} s", run_dir, t_req, t.front(),
                   t.back());
      continue;
    }
    const RingMoment m = ringMoment(trace, trace.rowNearest(t_req), chambers, wheels);
    write(at(ringPictureName(t_req)), drawRingPicture(geometry, robot.body.diameter_m, m, scales), written);
  }
  return written;
}

}  // namespace climbsim::plot
