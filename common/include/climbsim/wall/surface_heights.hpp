#pragma once
/// @file
/// The wall's surface as heights over the wall plane, and where a sphere (a wheel) standing on
/// it rests (docs/design.md#drive): what the drive's wheels stand on, from the same static
/// triangles the depth camera renders, without rendering.
///
/// Frame: the wall frame W (x, y in the wall plane, z out of the wall). The surface height
/// h(x, y) is sampled at the grid points (i cell, j cell): the highest z_W at which the line
/// along W's z through the point meets a triangle, if that is no deeper than reach_m below the
/// wall plane (z_W >= -reach_m); else there is no surface there (a hole deeper than the
/// sensors reach, or past the edge of the scene). Triangles standing on edge (a step's face)
/// are met by no such line: the grid sees a step as a jump between two neighbouring points.
///
/// The grid is built in tiles of kTileCells x kTileCells points at the first query that needs
/// them (a pure function of the triangles: every process that asks gets the same heights), so
/// only the strip of wall the robot crosses costs memory.

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "climbsim/wall/scene.hpp"

namespace climbsim::scene {

/// Where a sphere of radius r above the point (x, y) of the wall plane rests on the surface.
struct SphereRest {
  /// False when no surface lies under the sphere's footprint (the disc of radius r about (x, y)).
  bool touches = false;
  /// The lowest height of the sphere's centre above the wall plane at which it does not cut
  /// the surface [m]: z_c = max over surface points p within r of (x, y) of
  /// h(p) + sqrt(r² - |p - (x, y)|²); h + r on a level surface.
  double centre_z_m = 0.0;
  /// The surface point that decides it (x, y, h) in W [m].
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  /// Unit normal of the surface at the contact, towards the sphere: (c - p) / r with c the
  /// resting centre for a grid point (moved between the grid points to the vertex of a parabola
  /// through it and its neighbours along x and y, except across an edge); for the point
  /// straight below the centre, the normal of the bilinear surface there, (-dh/dx, -dh/dy, 1)
  /// normalised.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// True when the contact is the point straight below the centre on a level patch (both
  /// slopes exactly 0): normal exactly W's z, point (x, y, h).
  bool level = false;
};

class SurfaceHeights {
 public:
  /// Grid step [m]: 1 mm, finer than a wheel's Hertz flattening under load.
  static constexpr double kDefaultCell_m = 0.001;
  /// Points per tile side; a 4 x 4 block of points is the unit of the search's bound.
  static constexpr int kTileCells = 64;
  static constexpr int kBlockCells = 4;

  /// From triangles already in the wall frame W [m] (moved in). reach_m >= 0; cell_m > 0.
  /// patch_m >= 0: the tyre's contact patch over which the heights are enveloped (below); 0
  /// keeps the sampled surface.
  SurfaceHeights(TriangleMesh mesh_W, double reach_m, double cell_m = kDefaultCell_m, double patch_m = 0.0);
  ~SurfaceHeights();
  SurfaceHeights(SurfaceHeights&&) noexcept;
  SurfaceHeights& operator=(SurfaceHeights&&) noexcept;

  /// h at grid point (i, j) [m], -infinity where there is no surface. With a patch of
  /// 2k + 1 cells (k = round(patch_m / (2 cell_m))) h is the enveloped height: the mean of the
  /// sampled heights h_s over the (2k + 1)² points about (i, j) that have a surface (a tyre
  /// envelops roughness shorter than its contact patch: docs/design.md#drive), exactly h_s
  /// where they are all equal, no surface where none of them has one.
  double height(std::int64_t i, std::int64_t j) const;

  /// Where a sphere of radius `radius_m` above (x_m, y_m) rests (SphereRest). The candidates
  /// are the grid points within the radius and the point straight below the centre on the
  /// bilinear surface of its four neighbouring grid points (when all four have a surface);
  /// ties go to the latter. On a level surface this is h + r exactly.
  SphereRest sphereRest(double x_m, double y_m, double radius_m) const;

  double cell() const { return cell_m_; }
  double reach() const { return reach_m_; }

 private:
  struct Tile;
  const Tile& tile(std::int64_t ti, std::int64_t tj) const;
  Tile buildTile(std::int64_t ti, std::int64_t tj) const;
  /// The sampled heights of the n x n points from (i0, j0), row-major in j.
  std::vector<float> sampled(std::int64_t i0, std::int64_t j0, std::int64_t n) const;

  TriangleMesh mesh_;
  double reach_m_ = 0.0;
  double cell_m_ = kDefaultCell_m;
  int patch_half_cells_ = 0;  ///< k of the enveloping patch (2k + 1 cells)
  /// Per tile the triangles whose box overlaps it (key: tileKey(ti, tj)).
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> buckets_;
  mutable std::unordered_map<std::int64_t, std::unique_ptr<Tile>> tiles_;
  /// The tiles found by lookups (tiles never move once built) and their keys, one slot per
  /// tile of an 8 x 8 window that repeats across the wall (slot (ti mod 8, tj mod 8)): the
  /// wheels' queries stay on a few tiles for thousands of steps. A move takes them along with
  /// the tiles.
  struct RecentTiles {
    static constexpr int kSide = 8;
    std::array<const Tile*, kSide * kSide> tile{};
    std::array<std::int64_t, kSide * kSide> key{};
    RecentTiles() = default;
    RecentTiles(RecentTiles&& o) noexcept : tile(std::exchange(o.tile, {})), key(o.key) {}
    RecentTiles& operator=(RecentTiles&& o) noexcept {
      tile = std::exchange(o.tile, {}), key = o.key;
      return *this;
    }
  };
  mutable RecentTiles recent_;
};

/// The surface of `scene`'s static parts in the wall frame of `pose_element` (wall_coverage.hpp's
/// wallPartOf), enveloped over `patch_m` (SurfaceHeights). The parts below the wall part are
/// taken into W along the scene tree from it (a face attached to the wall part with no offset
/// keeps its coordinates exactly), the others through the world frame.
SurfaceHeights surfaceHeights(const Scene& scene, const std::string& pose_element, double reach_m,
                              double cell_m = SurfaceHeights::kDefaultCell_m, double patch_m = 0.0);

}  // namespace climbsim::scene
