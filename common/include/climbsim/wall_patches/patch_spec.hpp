#pragma once
/// @file
/// What a wall patch is made of: a cube of edge size_m whose front face (the structured
/// face) carries rough concrete and features. Plain values in SI units; read from YAML or
/// the command line by patch_spec_yaml.hpp.
///
/// Patch frame P (the frame of the written mesh): the structured face spans
/// x in [0, size_m], y in [0, size_m]; z points out of the wall; the mean plane of the
/// rough concrete is z = 0; the cube's back face is z = -size_m. Angles are measured in the
/// face from +x towards +y.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace climbsim::surface {

/// Cross-section of a crack or groove, as depth (fraction of depth_m) over the distance s
/// from its centre line. Every profile is piecewise linear between breakpoints that the
/// mesh carries as vertex lines, so the mesh holds the profile exactly.
enum class Profile {
  kRect,  ///< flat floor at depth_m; the walls run over wall_run (PatchSpec) at |s| = width/2
  kV,     ///< depth_m at s = 0, falling linearly to 0 at |s| = width/2
  kU,     ///< elliptic: depth_m sqrt(1 - (2s/width)^2), 8 linear pieces per side
};

/// Gaussian-correlated roughness: heights with autocorrelation rms^2 exp(-r^2 / l^2)
/// (l = correlation length, the 1/e distance), zero mean and RMS exactly rms_m over the
/// grid vertices.
struct Roughness {
  double rms_m = 0.001;                 ///< >= 0; 0 gives a flat face
  double correlation_length_m = 0.02;   ///< >= 0; 0 gives white noise on the grid
};

/// A straight crack or groove: centre line through (x_m, y_m) at angle_deg.
struct LinearFeature {
  double x_m = 1.0;
  double y_m = 1.0;
  double angle_deg = 0.0;
  double width_m = 0.01;    ///< at the surface, > 0
  double depth_m = 0.01;    ///< below the local rough surface, > 0
  double length_m = 0.0;    ///< 0: across the whole face; else centred on (x_m, y_m), round ends
  Profile profile = Profile::kRect;
};

/// Seeded crack polylines: each starts at a uniform point of the face with a uniform
/// direction and turns by N(0, turn_deg) at every joint; a polyline ends at the face border.
struct CrackNetwork {
  int count = 0;                   ///< number of polylines, >= 0
  int segments = 6;                ///< segments per polyline, >= 1
  double segment_length_m = 0.15;  ///< > 0
  double turn_deg = 25.0;          ///< standard deviation of the turn at a joint, >= 0
  double width_m = 0.004;          ///< > 0
  double depth_m = 0.015;          ///< > 0
  Profile profile = Profile::kV;
};

/// A circular hole with a flat bottom, as a regular polygon circumscribed about the circle
/// (its sides touch the circle, on the x and y axes through the centre among others; its
/// corners lie at most run / 2 outside it); the wall runs over run = min(wall_run_m, r / 5)
/// inwards, so the floor covers at least the circle of radius r - run.
struct Hole {
  double x_m = 1.0;
  double y_m = 1.0;
  double diameter_m = 0.05;  ///< > 0
  double depth_m = 0.03;     ///< > 0
};

/// A step: along the line through (x_m, y_m) at angle_deg, the side to the left of the
/// line direction (normal = direction turned by +90 deg) is raised by height_m (negative
/// lowers it); the ramp spans wall_run_m centred on the line.
struct Step {
  double x_m = 1.0;
  double y_m = 1.0;
  double angle_deg = 0.0;
  double height_m = 0.01;  ///< != 0
};

/// Everything of one patch. validate() before use.
struct PatchSpec {
  double size_m = 2.0;         ///< cube edge, > 0
  double grid_m = 0.004;       ///< heightfield spacing of the structured face (rounded so size/grid is whole), > 0
  double wall_run_m = 0.0002;  ///< horizontal run of the steep walls of rect cracks, holes and steps, > 0
  std::uint64_t seed = 1;
  Roughness rough;
  std::vector<LinearFeature> cracks;
  std::vector<LinearFeature> grooves;
  CrackNetwork network;
  std::vector<Hole> holes;
  std::vector<Step> steps;
};

/// Names where a key came from, e.g. "spec.yaml:12" or "--crack"; for messages only.
using KeyLocator = std::function<std::string(const std::string& key)>;

/// Throws ConfigError "<where(key)>: <key> = <value>: <problem>" for the first bad value;
/// keys are YAML paths ("cracks[0].width_m").
void validatePatchSpec(const PatchSpec& spec, const KeyLocator& where);

/// "rect", "v", "u".
const char* profileName(Profile profile);

}  // namespace climbsim::surface
