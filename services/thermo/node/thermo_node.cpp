#include "thermo_node.hpp"

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

LeakageMerger::LeakageMerger(std::vector<std::string> segment_names, std::vector<double> initial_leak_area_m2)
    : names_(std::move(segment_names)), leak_area_m2_(std::move(initial_leak_area_m2)) {
  if (names_.size() != leak_area_m2_.size()) {
    throw std::invalid_argument("LeakageMerger: " + std::to_string(names_.size()) + " names but " +
                                std::to_string(leak_area_m2_.size()) + " areas");
  }
  for (std::size_t i = 0; i < names_.size(); ++i) index_.emplace(names_[i], i);
}

std::string LeakageMerger::check(const climbsim::Leakage& part) const {
  std::set<std::string> seen;
  for (const auto& s : part.segments()) {
    const std::string name = s.segment().c_str();
    if (index_.count(name) == 0) return "segment '" + name + "' is not a segment of the robot";
    if (!seen.insert(name).second) return "segment '" + name + "' given twice";
    if (!std::isfinite(s.leak_area_m2()) || s.leak_area_m2() < 0.0) {
      return "segment '" + name + "': leak_area_m2 = " + fmt(s.leak_area_m2()) + " (must be finite and >= 0)";
    }
    if (!std::isfinite(s.mean_gap_m())) {
      return "segment '" + name + "': mean_gap_m = " + fmt(s.mean_gap_m()) + " (must be finite)";
    }
  }
  return {};
}

const std::vector<double>& LeakageMerger::merge(const std::vector<climbsim::Leakage>& parts) {
  std::set<std::string> covered;
  for (const auto& part : parts) {
    std::string reason = check(part);
    if (reason.empty()) {
      for (const auto& s : part.segments()) {
        if (covered.count(s.segment().c_str()) != 0) {
          reason = std::string("segment '") + s.segment().c_str() + "' also given by another part of this step";
          break;
        }
      }
    }
    if (!reason.empty()) {
      ++dropped_;
      spdlog::warn("sealing/Leakage from '{}' at step {}: {}; dropped ({} so far), last valid areas held",
                   part.source().c_str(), part.step(), reason, dropped_);
      continue;
    }
    for (const auto& s : part.segments()) {
      covered.insert(s.segment().c_str());
      leak_area_m2_[index_.at(s.segment().c_str())] = s.leak_area_m2();
    }
  }
  return leak_area_m2_;
}

ThermoNodeInputs parseThermoNodeInputs(const std::string& list) {
  ThermoNodeInputs inputs{false, false, false};
  if (list == "none") return inputs;
  for (const auto& name : parseNameList("--inputs", list)) {
    if (name == "leakage") {
      inputs.leakage = true;
    } else if (name == "valves") {
      inputs.valves = true;
    } else if (name == "engines") {
      inputs.engines = true;
    } else {
      throw ConfigError("--inputs = '" + list + "': unknown input '" + name +
                        "' (choose from leakage, valves, engines, or none)");
    }
  }
  return inputs;
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
void ThermoNode::applyCommands(const std::vector<Sample>& samples, const char* topic, std::uint64_t& dropped,
                               const Apply& apply) {
  for (const auto& sample : samples) {
    ThermoInputs candidate = inputs_;
    apply(candidate, sample);
    const std::string reason = validateInputs(model_.params(), candidate);
    if (!reason.empty()) {
      ++dropped;
      spdlog::warn("{} from '{}' at step {}: {}; dropped ({} so far), last valid held", topic,
                   sample.source().c_str(), sample.step(), reason, dropped);
      continue;
    }
    inputs_ = std::move(candidate);
  }
}

ThermoOutputs ThermoNode::step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::Leakage>& leakage,
                               const std::vector<climbsim::ValveCommand>& valves,
                               const std::vector<climbsim::EngineCommand>& engines) {
  if (!leakage.empty()) inputs_.leak_area_m2 = merger_.merge(leakage);
  applyCommands(valves, "controller/ValveCommand", dropped_valves_,
                [](ThermoInputs& in, const climbsim::ValveCommand& s) { in.valve_command = valveCommandFromIdl(s); });
  applyCommands(engines, "controller/EngineCommand", dropped_engines_,
                [](ThermoInputs& in, const climbsim::EngineCommand& s) { in.engines = engineCommandsFromIdl(s); });
  if (!state_) state_ = model_.initialState(t_ns);
  return model_.step(*state_, inputs_, t_ns, dt_ns);
}

}  // namespace climbsim::thermo
