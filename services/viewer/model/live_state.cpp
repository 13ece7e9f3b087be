#include "live_state.hpp"

namespace climbsim::viewer {

const char* phaseName(RunPhase phase) {
  switch (phase) {
    case RunPhase::kStarting: return "starting";
    case RunPhase::kRunning: return "running";
    case RunPhase::kPaused: return "paused";
    case RunPhase::kCompleted: return "completed";
    case RunPhase::kStopped: return "stopped";
    case RunPhase::kFailed: return "failed";
  }
  return "unknown";
}

namespace {
/// Latest value wins, but a late older sample (best effort has no order across writers)
/// never replaces a newer one.
template <class T>
bool offerNewest(std::optional<T>& slot, const T& value) {
  if (slot && slot->step > value.step) return false;
  slot = value;
  return true;
}

double seconds(std::int64_t t_ns) { return static_cast<double>(t_ns) * 1e-9; }
}  // namespace

void RateMeter::add(std::int64_t wall_ns, std::int64_t sim_ns) {
  constexpr std::int64_t kWindowNs = 1'000'000'000;
  if (base_wall_ns_ < 0 || sim_ns < last_sim_ns_) {  // first sample, or a new run
    base_wall_ns_ = last_wall_ns_ = wall_ns;
    base_sim_ns_ = last_sim_ns_ = sim_ns;
    rate_ = 0.0;
    return;
  }
  last_wall_ns_ = wall_ns;
  last_sim_ns_ = sim_ns;
  if (wall_ns - base_wall_ns_ >= kWindowNs / 4) {
    rate_ = static_cast<double>(sim_ns - base_sim_ns_) / static_cast<double>(wall_ns - base_wall_ns_);
  }
  if (wall_ns - base_wall_ns_ >= kWindowNs) {
    base_wall_ns_ = wall_ns;
    base_sim_ns_ = sim_ns;
  }
}

bool LiveState::offer(const ForceValue& value) { return offerNewest(force, value); }
bool LiveState::offer(const ChamberValue& value) { return offerNewest(chambers, value); }
bool LiveState::offer(const PoseValue& value) { return offerNewest(pose, value); }
bool LiveState::offer(const WheelsValue& value) { return offerNewest(wheels, value); }

bool LiveState::offer(const LeakValue& value) {
  if (leak && leak->step > value.step) return false;
  if (!leak || leak->step < value.step) {
    leak = value;
    return true;
  }
  for (const auto& [name, area_gap] : value.segments) leak->segments[name] = area_gap;
  return true;
}

nlohmann::json sampleJson(const LiveState& state) {
  using nlohmann::json;
  json frame = json::object();
  if (state.force) {
    const auto& f = *state.force;
    frame["force"] = {{"step", f.step}, {"t_s", seconds(f.t_ns)}, {"downforce_n", f.downforce_n},
                      {"pf_x_m", f.pf_x_m}, {"pf_y_m", f.pf_y_m}};
    // The set-point of whichever controller ran, as thermo publishes it (null: none).
    frame["force"]["setpoint_n"] = f.setpoint_n > 0.0 ? nlohmann::json(f.setpoint_n) : nlohmann::json(nullptr);
  }
  if (state.chambers) {
    const auto& c = *state.chambers;
    frame["chambers"] = {{"step", c.step}, {"t_s", seconds(c.t_ns)}, {"pressure_pa", c.pressure_pa},
                         {"valve_opening", c.valve_opening}};
  }
  if (state.pose) {
    const auto& p = *state.pose;
    frame["pose"] = {{"step", p.step}, {"t_s", seconds(p.t_ns)}, {"position_m", p.position_m},
                     {"orientation_wxyz", p.orientation_wxyz}, {"fell", p.fell}};
  }
  if (state.wheels) {
    const auto& w = *state.wheels;
    frame["wheels"] = {{"step", w.step}, {"t_s", seconds(w.t_ns)}, {"normal_n", w.normal_n},
                       {"slip_mps", w.slip_mps}, {"steering_rad", w.steering_rad}};
  }
  return frame;
}

void SampleHistory::add(const LiveState& state) {
  const auto step = [](const auto& slot) { return slot ? static_cast<std::int64_t>(slot->step) : -1; };
  const std::array<std::int64_t, 4> steps{step(state.force), step(state.chambers), step(state.pose), step(state.wheels)};
  if (steps == last_steps_ || steps == std::array<std::int64_t, 4>{-1, -1, -1, -1}) return;
  last_steps_ = steps;
  if (samples_.size() >= capacity_) samples_.erase(samples_.begin());
  samples_.push_back(sampleJson(state));
}

nlohmann::json SampleHistory::take() {
  nlohmann::json out = nlohmann::json::array();
  for (auto& sample : samples_) out.push_back(std::move(sample));
  samples_.clear();
  return out;
}

nlohmann::json frameJson(const LiveState& state) {
  using nlohmann::json;
  const RunInfo& run = state.run;
  json roster = json::array();
  for (const auto& member : run.roster) {
    const auto host = run.hosts.find(member.name);
    roster.push_back({{"name", member.name}, {"host", host != run.hosts.end() ? host->second : member.host}, {"period", member.period_steps},
                      {"offset", member.offset_steps}});
  }
  json frame = {{"type", "frame"},
                {"run",
                 {{"phase", phaseName(run.phase)},
                  {"reason", run.reason},
                  {"step", run.step},
                  {"t_s", seconds(run.t_ns)},
                  {"dt_s", seconds(run.dt_ns)},
                  {"end_s", seconds(run.dt_ns) * static_cast<double>(run.end_step)},
                  {"rtf_target", run.rtf_target},
                  {"rtf_measured", run.rtf_measured},
                  {"roster", roster}}},
                {"depth_version", state.depth_version},
                {"sealing_versions", state.sealing_versions}};
  frame.update(sampleJson(state));
  if (state.leak) {
    json segments = json::object();
    for (const auto& [name, area_gap] : state.leak->segments) {
      segments[name] = {{"leak_area_m2", area_gap.first}, {"mean_gap_m", area_gap.second}};
    }
    frame["leak"] = {{"step", state.leak->step}, {"t_s", seconds(state.leak->t_ns)}, {"segments", segments}};
  }
  return frame;
}

}  // namespace climbsim::viewer
