#pragma once
/// @file
/// File names of the pictures of a run, shared by climbsim-plot (plots/ring_<t>s.png) and the
/// recorder (pictures/sealing_<kind>_<t>s.png): <t> is the requested time in seconds as
/// written in the scenario, shortest form ("1", "2.5", "0.125"; millisecond resolution).

#include <cstdio>
#include <string>

namespace climbsim::plot {

/// "1" for 1.0, "2.5" for 2.5, "0.125" for 0.125: %.3f without trailing zeros.
inline std::string pictureTimeLabel(double t_s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", t_s);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

inline std::string ringPictureName(double t_s) { return "ring_" + pictureTimeLabel(t_s) + "s.png"; }

inline std::string sealingPictureName(const std::string& kind, double t_s) {
  return "sealing_" + kind + "_" + pictureTimeLabel(t_s) + "s.png";
}

}  // namespace climbsim::plot
