#include "climbsim/shard_tiles/sealing_params.hpp"

namespace climbsim::sealing {

SealingParams sealingParamsFromRobot(const RobotDescription& robot, const RobotGeometry& geometry) {
  SealingParams p;
  p.max_slope = robot.sealing.max_slope;
  p.travel_m = robot.sealing.travel_m;
  p.basic_gap_m = robot.sealing.basic_gap_m;
  p.kappa_L = robot.sealing.kappa_L;
  p.channel_bound = robot.sealing.channel_bound;
  for (const auto& s : geometry.segments) {
    p.segment_names.push_back(s.name);
    p.segment_length_m.push_back(s.length_m);
  }
  return p;
}

}  // namespace climbsim::sealing
