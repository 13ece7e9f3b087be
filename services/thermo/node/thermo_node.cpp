#include "thermo_node.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"
#include "thermo_translate.hpp"

namespace climbsim::thermo {
namespace {

std::string fmt(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

}  // namespace

ThermoNodeInputs parseThermoNodeInputs(const std::string& list) {
  const auto chosen = parseChoiceList("--inputs", list, {"leakage", "valves", "engines"});
  return ThermoNodeInputs{chosen.count("leakage") != 0, chosen.count("valves") != 0, chosen.count("engines") != 0};
}

ThermoNode::ThermoNode(ThermoParams params, std::vector<std::string> segment_names,
                       std::vector<double> basic_leak_area_m2)
    : model_(std::move(params)), merger_(std::move(segment_names), std::move(basic_leak_area_m2)) {
  inputs_.leak_area_m2 = merger_.leakAreas();
  inputs_.engines.assign(model_.params().engines.size(), EngineCommand{false, 1.0});
  const std::string reason = validateInputs(model_.params(), inputs_);
  if (!reason.empty()) throw ConfigError("thermo default inputs: " + reason);
}

template <class Sample, class Apply>
bool ThermoNode::applyCommand(const Sample& sample, const char* topic, std::uint64_t& dropped, const Apply& apply) {
  ThermoInputs candidate = inputs_;
  apply(candidate, sample);
  const std::string reason = validateInputs(model_.params(), candidate);
  if (!reason.empty()) {
    ++dropped;
    spdlog::warn("{} from '{}' at step {}: {}; dropped ({} so far), last valid held", topic, sample.source().c_str(),
                 sample.step(), reason, dropped);
    return false;
  }
  inputs_ = std::move(candidate);
  return true;
}

ThermoOutputs ThermoNode::step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::Leakage>& leakage,
                               const std::vector<climbsim::ValveCommand>& valves,
                               const std::vector<climbsim::EngineCommand>& engines) {
  if (!leakage.empty()) inputs_.leak_area_m2 = merger_.merge(leakage);
  for (const auto& sample : valves) {
    const double setpoint_n = sample.downforce_setpoint_n();
    if (!(std::isfinite(setpoint_n) && setpoint_n >= 0.0 && setpoint_n <= 1e6)) {
      ++dropped_valves_;
      spdlog::warn("controller/ValveCommand from '{}' at step {}: downforce_setpoint_n = {} (must be finite, in [0, "
                   "1e6] N; 0: none); dropped ({} so far), last valid held",
                   sample.source().c_str(), sample.step(), fmt(setpoint_n), dropped_valves_);
      continue;
    }
    if (applyCommand(sample, "controller/ValveCommand", dropped_valves_,
                     [](ThermoInputs& in, const climbsim::ValveCommand& s) { in.valve_command = valveCommandFromIdl(s); })) {
      setpoint_n_ = setpoint_n;
    }
  }
  for (const auto& sample : engines) {
    applyCommand(sample, "controller/EngineCommand", dropped_engines_,
                 [](ThermoInputs& in, const climbsim::EngineCommand& s) { in.engines = engineCommandsFromIdl(s); });
  }
  if (!state_) state_ = model_.initialState(t_ns);
  if (faults_.empty()) return model_.step(*state_, inputs_, t_ns, dt_ns);
  return model_.step(*state_, applyFaults(t_ns), t_ns, dt_ns);
}

void ThermoNode::setFaults(const std::vector<Scenario::Fault>& faults, const std::string& source) {
  std::vector<PlantFault> out;
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const auto& f = faults[i];
    const std::string key = source + ": faults[" + std::to_string(i) + "]";
    if (f.kind == Scenario::FaultKind::kValveStuck && (f.chamber < 1 || f.chamber > kNumChambers)) {
      throw ConfigError(key + ".chamber = " + std::to_string(f.chamber) + ": chambers are 1.." +
                        std::to_string(kNumChambers));
    }
    if (f.kind == Scenario::FaultKind::kValveStuck && !(f.opening >= 0.0 && f.opening <= 1.0)) {
      throw ConfigError(key + ".opening = " + fmt(f.opening) + ": must be in [0, 1]");
    }
    const auto engines = static_cast<int>(model_.params().engines.size());
    if (f.kind == Scenario::FaultKind::kEngineFailure && (f.engine < 1 || f.engine > engines)) {
      throw ConfigError(key + ".engine = " + std::to_string(f.engine) + ": the robot has " + std::to_string(engines) +
                        " engine(s), 1.." + std::to_string(engines));
    }
    if (!std::isfinite(f.t_s)) throw ConfigError(key + ".t_s = " + fmt(f.t_s) + ": must be finite");
    out.push_back({f, static_cast<std::int64_t>(std::llround(f.t_s * 1e9)), false});
  }
  faults_ = std::move(out);
}

ThermoInputs ThermoNode::applyFaults(std::int64_t t_ns) {
  ThermoInputs in = inputs_;
  for (auto& pf : faults_) {
    if (pf.t_ns > t_ns) continue;
    const auto& f = pf.fault;
    if (f.kind == Scenario::FaultKind::kValveStuck) {
      const auto c = static_cast<std::size_t>(f.chamber - 1);
      // Held equal to the target, the command queues nothing (queueValveCommands).
      in.valve_command[c] = f.opening;
      if (!pf.active) {
        // The valve sticks now, not one command delay later, and no command already on its
        // way reaches it.
        state_->valve_target[c] = f.opening;
        auto& pending = state_->pending_valve_commands;
        pending.erase(std::remove_if(pending.begin(), pending.end(),
                                     [&](const PendingValveCommand& p) { return p.chamber == f.chamber - 1; }),
                      pending.end());
        spdlog::warn("thermo: fault at t = {} s: the valve of chamber {} is stuck, it goes to opening {} and "
                     "ignores commands",
                     static_cast<double>(t_ns) * 1e-9, f.chamber, f.opening);
      }
    } else {
      in.engines[static_cast<std::size_t>(f.engine - 1)].on = false;
      if (!pf.active) {
        spdlog::warn("thermo: fault at t = {} s: suction engine {} failed, it stops whatever is commanded",
                     static_cast<double>(t_ns) * 1e-9, f.engine);
      }
    }
    pf.active = true;
  }
  return in;
}

}  // namespace climbsim::thermo
