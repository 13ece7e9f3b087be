#pragma once
/// @file
/// Test-only: the default CROMSCI robot of docs/robot-files.md#default-values as ThermoParams,
/// typed in here independently of the robot geometry (common/robot) that configures the service.
/// Chamber 7 is the centre disc r < 0.15 m; chambers 1..6 are 60° ring sectors
/// 0.15..0.36 m, chamber 1 centred on +x, counter-clockwise. Segments 0..5: outer arcs
/// (chamber i <-> ambient), 6..11: radial walls (chamber i <-> i+1, cyclic), 12..17:
/// inner arcs (chamber i <-> centre).

#include <algorithm>
#include <cmath>
#include <vector>

#include "thermo_model.hpp"

namespace climbsim::thermo::testing {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInnerRadiusM = 0.15;
constexpr double kOuterRadiusM = 0.36;
constexpr double kBasicLeakGapM = 1e-4;  ///< L_basic
constexpr int kOuterArc0 = 0;
constexpr int kRadialWall0 = 6;
constexpr int kInnerArc0 = 12;
constexpr int kNumSegments = 18;

inline ThermoParams defaultCromsciParams() {
  ThermoParams p;
  p.chamber_volume_m3.assign(6, 2.2e-3);
  p.chamber_volume_m3.push_back(2.8e-3);
  p.has_reservoir = true;
  p.reservoir_volume_m3 = 15e-3;
  p.chamber_area_m2.resize(7);
  p.p_RobotChamber_m.resize(7);

  const double half_angle = kPi / 6.0;
  const double ring = kOuterRadiusM * kOuterRadiusM - kInnerRadiusM * kInnerRadiusM;
  const double sector_area = half_angle * ring;
  // Centroid radius of an annular sector: (2/3)(r2^3 - r1^3)/(r2^2 - r1^2) sin(a)/a.
  const double centroid_radius = 2.0 / 3.0 *
                                 (std::pow(kOuterRadiusM, 3) - std::pow(kInnerRadiusM, 3)) / ring *
                                 std::sin(half_angle) / half_angle;
  for (int i = 0; i < 6; ++i) {
    const double angle = i * kPi / 3.0;
    p.chamber_area_m2[i] = sector_area;
    p.p_RobotChamber_m[i] = {centroid_radius * std::cos(angle), centroid_radius * std::sin(angle)};
  }
  p.chamber_area_m2[6] = kPi * kInnerRadiusM * kInnerRadiusM;
  p.p_RobotChamber_m[6] = {0.0, 0.0};

  for (int i = 0; i < 6; ++i) p.segments.push_back({i, kAmbient});
  for (int i = 0; i < 6; ++i) p.segments.push_back({i, (i + 1) % 6});
  for (int i = 0; i < 6; ++i) p.segments.push_back({i, 6});

  p.engines.assign(3, SuctionEngineParams{22e3, 40e-3, 0.5});
  p.valve = ValveParams{7e-4, 0.6, 0.2, 0.02};
  return p;
}

/// Lengths of the 18 segments [m], in the order of defaultCromsciParams().
inline std::vector<double> cromsciSegmentLengths() {
  std::vector<double> l;
  for (int i = 0; i < 6; ++i) l.push_back(kOuterRadiusM * kPi / 3.0);
  for (int i = 0; i < 6; ++i) l.push_back(kOuterRadiusM - kInnerRadiusM);
  for (int i = 0; i < 6; ++i) l.push_back(kInnerRadiusM * kPi / 3.0);
  return l;
}

/// Leak areas L_basic * l_i of a flat wall [m^2].
inline std::vector<double> basicLeakAreas() {
  std::vector<double> a = cromsciSegmentLengths();
  for (double& x : a) x *= kBasicLeakGapM;
  return a;
}

/// Basic leaks, valves closed, engines off (command speed 1).
inline ThermoInputs idleInputs(const ThermoParams& params) {
  ThermoInputs in;
  in.leak_area_m2 = params.segments.size() == kNumSegments ? basicLeakAreas()
                                                           : std::vector<double>(params.segments.size(), 0.0);
  in.valve_command.assign(static_cast<std::size_t>(params.valveCount()), 0.0);
  in.engines.assign(params.engines.size(), EngineCommand{false, 1.0});
  return in;
}

/// All engines on at full speed, every valve at `opening`.
inline ThermoInputs suctionInputs(const ThermoParams& params, double opening) {
  ThermoInputs in = idleInputs(params);
  for (auto& e : in.engines) e.on = true;
  std::fill(in.valve_command.begin(), in.valve_command.end(), opening);
  return in;
}

/// Steps `steps` times with period dt_ns; returns the last outputs.
inline ThermoOutputs run(const ThermoModel& model, ThermoState& state, const ThermoInputs& in, int steps,
                         std::int64_t dt_ns = 5'000'000) {
  ThermoOutputs out;
  for (int k = 0; k < steps; ++k) out = model.step(state, in, state.t_ns, dt_ns);
  return out;
}

}  // namespace climbsim::thermo::testing
