#pragma once
/// @file
/// Patch specs from YAML files and from the command line's key=value lists.
///
/// ```
/// size_m: 2.0            # cube edge
/// grid_m: 0.004          # heightfield spacing of the structured face
/// wall_run_m: 0.0002     # run of the steep walls (rect profiles, holes, steps)
/// seed: 1
/// rough: {rms_m: 0.001, correlation_length_m: 0.02}
/// cracks:                # straight; length_m 0 (default): across the face
///   - {x_m: 1.0, y_m: 0.7, angle_deg: 0, width_m: 0.01, depth_m: 0.04, profile: rect}
/// grooves:
///   - {x_m: 1.0, y_m: 1.5, angle_deg: 90, width_m: 0.03, depth_m: 0.01, profile: u, length_m: 1.0}
/// crack_network: {count: 4, segments: 6, segment_length_m: 0.15, turn_deg: 25,
///                 width_m: 0.004, depth_m: 0.015, profile: v}
/// holes:
///   - {x_m: 0.5, y_m: 0.5, diameter_m: 0.05, depth_m: 0.03}
/// steps:
///   - {x_m: 1.0, y_m: 1.0, angle_deg: 0, height_m: 0.01}
/// ```
/// Absent keys keep their defaults (patch_spec.hpp); unknown keys are errors.

#include <string>

#include <yaml-cpp/yaml.h>

#include "climbsim/wall_patches/patch_spec.hpp"

namespace climbsim::surface {

/// Reads and validates a YAML patch spec. Throws ConfigError "<file>:<line>: <key> ...".
PatchSpec loadPatchSpecYaml(const std::string& path);

/// Merges the keys of `root` (a YAML map of the layout above) into `spec`; list entries
/// are appended. `source` names the origin in messages. Does not validate.
void mergePatchSpec(PatchSpec& spec, const YAML::Node& root, const std::string& source);

/// "key=value,key=value" (the command line's feature options) as a YAML map of strings.
/// Throws ConfigError "<option>: '<text>': ..." on a malformed list.
YAML::Node keyValueList(const std::string& text, const std::string& option);

/// Validates `spec`, naming "<source>:<line>" of a key that came from `root` when known.
void validatePatchSpecFrom(const PatchSpec& spec, const YAML::Node& root, const std::string& source);

}  // namespace climbsim::surface
