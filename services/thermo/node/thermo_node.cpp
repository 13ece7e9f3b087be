#include "thermo_node.hpp"

#include <cmath>
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
  inputs_.valve_command.assign(static_cast<std::size_t>(model_.params().valveCount()), 0.0);
  inputs_.engines.assign(model_.params().engines.size(), EngineCommand{false, 1.0});
  const std::string reason = validateInputs(model_.params(), inputs_);
  if (!reason.empty()) throw ConfigError("thermo default inputs: " + reason);
}

template <class Sample, class Apply>
bool ThermoNode::applyCommand(const Sample& sample, const char* topic, std::uint64_t& dropped, const Apply& apply) {
  ThermoInputs candidate = inputs_;
  std::string reason;
  try {
    apply(candidate, sample);
    reason = validateInputs(model_.params(), candidate);
  } catch (const InvalidInputError& e) {
    reason = e.what();  // e.g. a sample sized for another robot
  }
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
  ThermoOutputs out = model_.step(*state_, inputs_, t_ns, dt_ns);
  for (const std::size_t f : out.faults_taking_effect) logFault(model_.params().faults[f], t_ns);
  return out;
}

void ThermoNode::logFault(const PlantFault& fault, std::int64_t t_ns) {
  if (fault.kind == PlantFault::Kind::kValveStuck) {
    spdlog::warn("thermo: fault at t = {} s: the valve of chamber {} is stuck, it goes to opening {} and ignores "
                 "commands",
                 static_cast<double>(t_ns) * 1e-9, fault.chamber, fault.opening);
  } else {
    spdlog::warn("thermo: fault at t = {} s: suction engine {} failed, it stops whatever is commanded",
                 static_cast<double>(t_ns) * 1e-9, fault.engine);
  }
}

}  // namespace climbsim::thermo
