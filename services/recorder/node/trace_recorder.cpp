#include "node/trace_recorder.hpp"

#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "climbsim/errors.hpp"
#include "node/trace_numbers.hpp"

namespace climbsim::recorder {
namespace {

template <class Range>
bool allFinite(const Range& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

void append(std::string& line, double value) {
  line += ',';
  appendG17(line, value);
}

}  // namespace

std::vector<std::string> traceColumns(const std::vector<std::string>& segment_names, int wheel_count, int chamber_count,
                                      bool has_reservoir) {
  std::vector<std::string> c = {"t_s", "downforce_n", "pf_x_m", "pf_y_m"};
  for (int i = 1; i <= chamber_count; ++i) c.push_back("p" + std::to_string(i) + "_pa");
  if (has_reservoir) {
    c.push_back("pr_pa");
    for (int i = 1; i <= chamber_count; ++i) c.push_back("valve" + std::to_string(i));
  }
  for (const auto& s : segment_names) c.push_back("leak_area_m2_" + s);
  for (const char* k : {"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"}) c.push_back(k);
  for (int i = 1; i <= wheel_count; ++i) c.push_back("wheel" + std::to_string(i) + "_normal_n");
  for (int i = 1; i <= wheel_count; ++i) c.push_back("wheel" + std::to_string(i) + "_slip_mps");
  c.push_back("downforce_setpoint_n");
  return c;
}

std::array<double, 3> rollPitchYaw(const std::array<double, 4>& wxyz) {
  const Eigen::Quaterniond q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
  const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  return {roll, pitch, yaw};
}

TraceRecorder::TraceRecorder(std::vector<std::string> segment_names, std::vector<double> basic_leak_area_m2,
                             int wheel_count, int chamber_count, bool has_reservoir)
    : columns_(traceColumns(segment_names, wheel_count, chamber_count, has_reservoir)),
      leakage_(std::move(segment_names), std::move(basic_leak_area_m2)),
      wheel_count_(wheel_count),
      pressures_(static_cast<std::size_t>(chamber_count + (has_reservoir ? 1 : 0))),
      valves_(has_reservoir ? static_cast<std::size_t>(chamber_count) : 0) {}

void TraceRecorder::update(const std::vector<climbsim::ChamberState>& states,
                           const std::vector<climbsim::AdhesionForce>& forces,
                           const std::vector<climbsim::Leakage>& leakage,
                           const std::vector<climbsim::RobotState>& poses,
                           const std::vector<climbsim::DriveState>& drives) {
  const auto drop = [this](const char* topic, const std::string& source, std::uint64_t step, const char* why) {
    ++dropped_;
    spdlog::warn("recorder: dropped {} from {} at step {}: {}", topic, source, step, why);
  };
  for (const auto& s : states) {
    if (s.pressure_pa().size() != pressures_ || s.valve_opening().size() != valves_) {
      drop("ChamberState", s.source().c_str(), s.step(),
           (std::to_string(s.pressure_pa().size()) + " pressures and " + std::to_string(s.valve_opening().size()) +
            " valve openings; the robot has " + std::to_string(pressures_) + " and " + std::to_string(valves_))
               .c_str());
    } else if (allFinite(s.pressure_pa()) && allFinite(s.valve_opening())) {
      state_ = s;
    } else {
      drop("ChamberState", s.source().c_str(), s.step(), "a value is not finite");
    }
  }
  for (const auto& f : forces) {
    if (allFinite(std::array<double, 4>{f.downforce_n(), f.pf_x_m(), f.pf_y_m(), f.downforce_setpoint_n()})) {
      force_ = f;
    } else {
      drop("AdhesionForce", f.source().c_str(), f.step(), "a value is not finite");
    }
  }
  if (!leakage.empty()) leakage_.merge(leakage);
  for (const auto& part : leakage) {
    for (const auto& s : part.segments()) {
      if (!(s.no_surface_share() >= kSealOverNothingShare)) continue;
      over_nothing_pending_ = true;
      over_nothing_max_share_ = std::max(over_nothing_max_share_, std::min(1.0, s.no_surface_share()));
      const std::string name = s.segment().c_str();
      if (std::find(over_nothing_segments_.begin(), over_nothing_segments_.end(), name) ==
          over_nothing_segments_.end()) {
        over_nothing_segments_.push_back(name);
      }
    }
  }
  for (const auto& p : poses) {
    if (allFinite(p.position_m()) && allFinite(p.orientation_wxyz())) {
      pose_ = p;
      fell_ = fell_ || p.fell();
    } else {
      drop("RobotState", p.source().c_str(), p.step(), "a value is not finite");
    }
  }
  for (const auto& d : drives) {
    bool ok = static_cast<int>(d.wheels().size()) == wheel_count_;
    for (const auto& w : d.wheels()) ok = ok && std::isfinite(w.normal_force_n()) && std::isfinite(w.slip_mps());
    if (ok) {
      drive_ = d;
      fell_ = fell_ || d.fell();
    } else {
      drop("DriveState", d.source().c_str(), d.step(), "wrong wheel count or a value is not finite");
    }
  }
}

std::string TraceRecorder::row(std::int64_t t_ns) {
  if (endedAtFall()) {
    if (!fell_at_ns_) fell_at_ns_ = t_ns;
    return {};
  }
  const double nan = std::nan("");
  std::string line;
  // t_s from integer nanoseconds: exact for every step of a run shorter than 104 days.
  appendFixed9(line, static_cast<double>(t_ns) * 1e-9);
  append(line, force_ ? force_->downforce_n() : nan);
  append(line, force_ ? force_->pf_x_m() : nan);
  append(line, force_ ? force_->pf_y_m() : nan);
  for (std::size_t i = 0; i < pressures_; ++i) append(line, state_ ? state_->pressure_pa()[i] : nan);
  for (std::size_t i = 0; i < valves_; ++i) append(line, state_ ? state_->valve_opening()[i] : nan);
  for (double a : leakage_.leakAreas()) append(line, a);
  if (pose_) {
    for (double v : pose_->position_m()) append(line, v);
    for (double v : rollPitchYaw(pose_->orientation_wxyz())) append(line, v);
  } else {
    for (int i = 0; i < 6; ++i) append(line, nan);
  }
  for (int i = 0; i < wheel_count_; ++i) append(line, drive_ ? drive_->wheels()[i].normal_force_n() : nan);
  for (int i = 0; i < wheel_count_; ++i) append(line, drive_ ? drive_->wheels()[i].slip_mps() : nan);
  append(line, force_ ? force_->downforce_setpoint_n() : nan);
  line += '\n';
  if (force_ && force_->downforce_setpoint_n() > 0.0) setpoint_n_ = force_->downforce_setpoint_n();
  if (over_nothing_pending_ && !over_nothing_at_ns_) over_nothing_at_ns_ = t_ns;
  over_nothing_pending_ = false;
  if (drive_) {
    double slide_mps = INFINITY;
    for (const auto& w : drive_->wheels()) {
      max_slip_mps_ = std::max(max_slip_mps_, w.slip_mps());
      if (w.normal_force_n() > 0.0) slide_mps = std::min(slide_mps, w.slip_mps());
    }
    // No wheel on the wall: the chassis' own speed along it.
    if (!std::isfinite(slide_mps) && pose_) slide_mps = std::hypot(pose_->linear_velocity_mps()[0], pose_->linear_velocity_mps()[1]);
    if (std::isfinite(slide_mps) && slide_mps > kSlideSpeedThresholdMps && rows_ > 0) {
      slide_m_ += slide_mps * static_cast<double>(t_ns - last_t_ns_) * 1e-9;
    }
  }
  if (force_ && t_ns >= downforce_from_ns_) {
    min_downforce_n_ = std::min(min_downforce_n_.value_or(force_->downforce_n()), force_->downforce_n());
    sum_downforce_n_ += force_->downforce_n();
    ++downforce_rows_;
    max_pf_shift_m_ = std::max(max_pf_shift_m_, std::hypot(force_->pf_x_m(), force_->pf_y_m()));
  }
  if (fell_ && !fell_at_ns_) fell_at_ns_ = t_ns;
  ++rows_;
  last_t_ns_ = t_ns;
  return line;
}

nlohmann::json TraceRecorder::summary() const {
  nlohmann::json j;
  j["steps"] = rows_;
  j["sim_s"] = static_cast<double>(last_t_ns_) * 1e-9;
  j["fell"] = fell_;
  j["fell_at_s"] = fell_at_ns_ ? nlohmann::json(static_cast<double>(*fell_at_ns_) * 1e-9) : nlohmann::json(nullptr);
  j["downforce_from_s"] = static_cast<double>(downforce_from_ns_) * 1e-9;
  j["min_downforce_n"] = min_downforce_n_ ? nlohmann::json(*min_downforce_n_) : nlohmann::json(nullptr);
  j["mean_downforce_n"] = downforce_rows_ > 0
                              ? nlohmann::json(sum_downforce_n_ / static_cast<double>(downforce_rows_))
                              : nlohmann::json(nullptr);
  j["max_pf_shift_m"] = downforce_rows_ > 0 ? nlohmann::json(max_pf_shift_m_) : nlohmann::json(nullptr);
  j["dropped_samples"] = droppedSamples();
  j["downforce_setpoint_n"] = setpoint_n_ ? nlohmann::json(*setpoint_n_) : nlohmann::json(nullptr);
  if (over_nothing_at_ns_) {
    j["seal_over_nothing"] = {{"first_at_s", static_cast<double>(*over_nothing_at_ns_) * 1e-9},
                              {"segments", over_nothing_segments_},
                              {"max_share", over_nothing_max_share_}};
  } else {
    j["seal_over_nothing"] = nullptr;
  }
  j["max_slip_mps"] = max_slip_mps_;
  j["slide_m"] = slide_m_;
  j["slide_limit_m"] = slide_limit_m_;
  const bool slid = slide_m_ > slide_limit_m_;
  j["slid"] = slid;
  j["adhesion_failed"] = fell_ || slid;
  return j;
}

void TraceRecorder::setDownforceFrom(std::int64_t t_ns) {
  if (t_ns < 0) throw ConfigError("recorder: the downforce statistics start at t = " + std::to_string(t_ns) + " ns (must be >= 0)");
  downforce_from_ns_ = t_ns;
}

void TraceRecorder::setSlideLimit(double slide_limit_m) {
  if (!(std::isfinite(slide_limit_m) && slide_limit_m > 0.0)) {
    throw ConfigError("recorder: slide_limit_m = " + std::to_string(slide_limit_m) + " (must be finite and > 0)");
  }
  slide_limit_m_ = slide_limit_m;
}

}  // namespace climbsim::recorder
