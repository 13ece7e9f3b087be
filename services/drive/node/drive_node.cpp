#include "drive_node.hpp"

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"
#include "drive_command.hpp"
#include "drive_translate.hpp"

namespace climbsim::drive {

DriveNodeInputs parseDriveNodeInputs(const std::string& list) {
  const auto chosen = parseChoiceList("--inputs", list, {"command", "adhesion"});
  return DriveNodeInputs{chosen.count("command") != 0, chosen.count("adhesion") != 0};
}

DriveNode::DriveNode(const DriveParams& params, const WallOrientation& wall, const StartPose& start,
                     double downforce_n)
    : model_(params, wall), start_(start) {
  inputs_.downforce_n = downforce_n;
  const std::string why = checkInputs(model_.params(), inputs_);
  if (!why.empty()) throw ConfigError("--downforce: " + why);
}

template <class Sample, class Apply>
void DriveNode::apply(const std::vector<Sample>& samples, const char* topic, std::uint64_t& dropped,
                      const Apply& apply) {
  for (const auto& sample : samples) {
    DriveInputs candidate = inputs_;
    apply(candidate, sample);
    const std::string why = checkInputs(model_.params(), candidate);
    if (!why.empty()) {
      ++dropped;
      spdlog::warn("{} from '{}' at step {}: {}; dropped ({} so far), last valid held", topic,
                   sample.source().c_str(), sample.step(), why, dropped);
      continue;
    }
    if (!sideways_noted_) {
      if (const std::string note = sidewaysNote(model_.params(), candidate.command); !note.empty()) {
        sideways_noted_ = true;
        spdlog::warn("{} from '{}' at step {}: {} (said once)", topic, sample.source().c_str(), sample.step(), note);
      }
    }
    inputs_ = std::move(candidate);
  }
}

const DriveOutputs& DriveNode::step(std::int64_t t_ns, std::int64_t dt_ns,
                                    const std::vector<climbsim::DriveCommand>& commands,
                                    const std::vector<climbsim::AdhesionForce>& adhesion) {
  apply(commands, topic::kDriveCommand, dropped_commands_,
        [](DriveInputs& in, const climbsim::DriveCommand& s) { in.command = driveCommandFromIdl(s); });
  apply(adhesion, topic::kAdhesionForce, dropped_adhesion_,
        [](DriveInputs& in, const climbsim::AdhesionForce& s) { applyAdhesion(s, in); });
  inputs_.held = t_ns < hold_until_ns_;
  if (!state_) state_ = model_.initialState(start_, t_ns);
  model_.step(*state_, inputs_, t_ns, dt_ns);
  return state_->outputs();
}

}  // namespace climbsim::drive
