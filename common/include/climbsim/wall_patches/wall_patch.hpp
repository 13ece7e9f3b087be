#pragma once
/// @file
/// A wall patch: the cube whose front face carries the rough concrete and the features.

#include <cstddef>
#include <cstdint>

#include "climbsim/wall_patches/patch_spec.hpp"
#include "climbsim/wall_patches/surface_mesh.hpp"

namespace climbsim::surface {

/// The mesh and what it is made of.
struct WallPatch {
  SurfaceMesh mesh;                 ///< patch frame (patch_spec.hpp)
  std::size_t face_triangles = 0;   ///< the first face_triangles triangles are the structured face
  int grid_cells = 0;               ///< cells per side of the base grid
  double grid_spacing_m = 0.0;      ///< size_m / grid_cells
};

/// Builds the cube of `spec` (validated by the caller): the structured face at z = rough +
/// features over a grid of round(size / grid) cells, with vertex lines at every profile
/// breakpoint; four side faces as strips from the face's rim down to z = -size (two
/// triangles per rim segment, so the cube is closed); the back face as two triangles.
/// Deterministic: the same spec gives the same mesh.
WallPatch generateWallPatch(const PatchSpec& spec);

/// The seed generateWallPatch draws a spec's crack network from (for tests and reports).
std::uint64_t crackNetworkSeed(std::uint64_t spec_seed);

}  // namespace climbsim::surface
