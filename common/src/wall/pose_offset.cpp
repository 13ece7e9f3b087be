#include "climbsim/wall/pose_offset.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <vector>

namespace climbsim::scene {

Eigen::Matrix3d rotationFromRollPitchYaw(double roll_rad, double pitch_rad, double yaw_rad) {
  return (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Pose poseFromXyzRpy(double x_m, double y_m, double z_m, double roll_rad, double pitch_rad, double yaw_rad) {
  Pose pose = Pose::Identity();
  pose.linear() = rotationFromRollPitchYaw(roll_rad, pitch_rad, yaw_rad);
  pose.translation() = Eigen::Vector3d(x_m, y_m, z_m);
  return pose;
}

bool parseNumber(const std::string& text, double& value) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  // from_chars rejects a leading '+', which people write in offsets.
  if (begin != end && *begin == '+') ++begin;
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end && begin != end && std::isfinite(value);
}

bool parseOffset(const std::string& text, Pose& pose, std::string& problem) {
  std::istringstream in(text);
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    double v = 0.0;
    if (!parseNumber(token, v)) {
      problem = "'" + token + "' is not a finite number";
      return false;
    }
    values.push_back(v);
  }
  if (values.size() != 6) {
    problem = "expected 6 numbers (x y z in m, roll pitch yaw in degrees), got " + std::to_string(values.size());
    return false;
  }
  constexpr double kRadPerDeg = M_PI / 180.0;
  pose = poseFromXyzRpy(values[0], values[1], values[2], values[3] * kRadPerDeg, values[4] * kRadPerDeg,
                        values[5] * kRadPerDeg);
  return true;
}

}  // namespace climbsim::scene
