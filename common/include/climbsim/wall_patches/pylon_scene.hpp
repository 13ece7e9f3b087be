#pragma once
/// @file
/// The default scene: a bridge pylon of 2 m concrete blocks and the robot's frames, as a SIMVIS3D scene
/// (docs/scene-files.md#scene-xml) with its meshes.
///
/// Wall frame W (insertion point WALL): origin on the wall in the rough concrete's mean
/// plane, x horizontal, y up, z out of the wall. WALL sits at ROOT offset (0, 0, 6) with roll
/// 90 deg, so in ROOT z is up and the pylon stands on z = 0.
///
/// Blocks: 3 columns x 4 rows of 2 m cubes, x in [-2, 4], y in [-6, 2] in W; block (c, r)
/// covers x in [-2 + 2c, 2c], y in [-2r, 2 - 2r]. The middle column (c = 1) is the robot's
/// path (the crack-descent scenario starts at x = 1.0, y = 1.2 and drives down -y):
///  - r = 0: a straight horizontal crack across the block at y = 0.70 m in W (0.50 m below
///    the start), 10 mm wide, 40 mm deep, rect profile;
///  - r = 1: a crack network (5 polylines, 4 mm wide, 15 mm deep, V profile);
///  - r = 2: holes;
///  - r = 3: a step and two grooves.
/// The middle column has a 5 mm grid, the side columns (rough only) a 10 mm grid; all blocks
/// rough concrete with 1 mm RMS and 20 mm correlation length, each block seeded from the
/// pylon seed. The right column's blocks are placed with yaw 180 deg (exercises offsets).

#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/scenario.hpp"
#include "climbsim/wall_patches/patch_spec.hpp"

namespace climbsim::surface {

/// The straight crack of block (1, 0), the one crack-descent drives over: rect profile, at
/// y = 0.70 m in W across the block. Its defaults are the shipped scene's.
struct PylonCrack {
  double width_m = Scenario::Crack::kDefaultWidth_m;  ///< opening [m]
  double depth_m = Scenario::Crack::kDefaultDepth_m;  ///< depth below the concrete's mean plane [m]
};

/// One block of the pylon.
struct PylonBlock {
  std::string name;      ///< insertion point name, e.g. "BLOCK_C1_R0"
  std::string mesh;      ///< file name under meshes/
  std::string kind;      ///< "crack", "network", "holes", "step_groove", "rough"
  int column = 0;        ///< 0..2, x
  int row = 0;           ///< 0..3, from the top
  double x_m = 0.0;      ///< lower-left corner of the structured face in W
  double y_m = 0.0;
  double yaw_deg = 0.0;  ///< 0 or 180: turned about its z, placed so that it covers the same square
  PatchSpec spec;
};

/// The default pylon's blocks for a seed (and the crack of block (1, 0)).
std::vector<PylonBlock> defaultPylonBlocks(std::uint64_t seed, const PylonCrack& crack = {});

/// Generation result per file, for the report.
struct WrittenMesh {
  std::string path;
  std::size_t triangles = 0;
};

/// Writes DIR/pylon.xml, DIR/walls/pylon_blocks.xml (nested, included by pylon.xml),
/// DIR/meshes/*.ply (the blocks), each mesh read back with assimp. ROBOT is a pure frame: the
/// scene service hangs the run's robot body under it (robot_body.hpp).
/// Throws ConfigError when DIR cannot be written or `crack` does not fit its block
/// (validatePatchSpec: "pylon block BLOCK_C1_R0: cracks[0].depth_m = ...").
std::vector<WrittenMesh> writePylonScene(const std::string& dir, std::uint64_t seed, const PylonCrack& crack = {});

}  // namespace climbsim::surface
