#include "run_plots.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "line_chart.hpp"
#include "picture_names.hpp"

namespace climbsim::plot {
namespace {

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

cv::Mat downforcePlot(const TraceTable& trace, double setpoint_n, const std::string& setpoint_label) {
  ChartSpec spec;
  spec.title = "Downforce F and its point of action P_F";
  Panel f{"F [N]", {series(trace, "downforce_n", "F", 0)}};
  if (std::isfinite(setpoint_n) && setpoint_n > 0.0) {
    f.series.push_back(constant(trace, setpoint_n, setpoint_label, paletteColour(3)));
  }
  Panel pf{"P_F in R [mm]", {series(trace, "pf_x_m", "P_F x", 1, 1e3), series(trace, "pf_y_m", "P_F y", 2, 1e3)}};
  spec.panels = {f, pf};
  return drawChart(spec);
}

cv::Mat pressuresPlot(const TraceTable& trace, int chamber_count, double ambient_pa) {
  ChartSpec spec;
  spec.title = "Chamber pressures p1..p" + std::to_string(chamber_count) + " and reservoir p_R";
  spec.panel_height_px = 560;
  Panel p{"p [kPa] (absolute)", {}};
  for (int i = 1; i <= chamber_count; ++i) {
    p.series.push_back(series(trace, "p" + std::to_string(i) + "_pa", "p" + std::to_string(i), i - 1, 1e-3));
  }
  p.series.push_back(series(trace, "pr_pa", "p_R", chamber_count, 1e-3));
  p.series.back().colour = cv::Scalar(0, 0, 0);
  p.series.push_back(constant(trace, ambient_pa * 1e-3, "ambient", cv::Scalar(150, 150, 150)));
  spec.panels = {p};
  return drawChart(spec);
}

cv::Mat valvesPlot(const TraceTable& trace, int valve_count) {
  ChartSpec spec;
  spec.title = "Valve openings (0 closed .. 1 open)";
  spec.panel_height_px = 520;
  Panel v{"opening [1]", {}};
  for (int i = 1; i <= valve_count; ++i) {
    v.series.push_back(series(trace, "valve" + std::to_string(i), "valve " + std::to_string(i), i - 1));
  }
  spec.panels = {v};
  return drawChart(spec);
}

cv::Mat wheelLoadsPlot(const TraceTable& trace, int wheel_count) {
  ChartSpec spec;
  spec.title = "Wheel normal loads and slip";
  Panel n{"normal load [N]", {}}, s{"slip speed [m/s]", {}};
  for (int i = 1; i <= wheel_count; ++i) {
    const std::string w = "wheel" + std::to_string(i);
    n.series.push_back(series(trace, w + "_normal_n", "wheel " + std::to_string(i), i - 1));
    s.series.push_back(series(trace, w + "_slip_mps", "wheel " + std::to_string(i), i - 1));
  }
  spec.panels = {n, s};
  return drawChart(spec);
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
  m.reservoir_pa = trace.column("pr_pa").at(row);
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

Setpoint downforceSetpoint(const Scenario& scenario, const RobotDescription& robot) {
  if (scenario.controller.kind == Scenario::ControllerKind::kReference) {
    const double f = scenario.controller.downforce_n > 0.0 ? scenario.controller.downforce_n
                                                           : robot.adhesion.desired_downforce_n;
    return {f, "set-point"};
  }
  return {robot.adhesion.desired_downforce_n, "robot's desired F"};
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
  std::vector<std::string> needed = {"t_s", "downforce_n", "pf_x_m", "pf_y_m", "pr_pa", "yaw_rad"};
  for (int i = 1; i <= chambers; ++i) {
    needed.push_back("p" + std::to_string(i) + "_pa");
    needed.push_back("valve" + std::to_string(i));
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
  write(at("downforce.png"), downforcePlot(trace, sp.downforce_n, sp.label), written);
  write(at("pressures.png"), pressuresPlot(trace, chambers, ambient), written);
  write(at("valves.png"), valvesPlot(trace, chambers), written);
  write(at("wheel_loads.png"), wheelLoadsPlot(trace, wheels), written);

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
