#pragma once
/// @file
/// Test helper: the height of a mesh's upward-facing surface at (x, y), by a 2D bin lookup
/// and barycentric interpolation (independent of the generator's own data structures).

#include <optional>
#include <string>
#include <vector>

#include "climbsim/wall_patches/surface_mesh.hpp"

namespace climbsim::surface::test {

class SurfaceSampler {
 public:
  /// Uses the triangles whose normal has a positive z component (the structured face).
  explicit SurfaceSampler(const SurfaceMesh& mesh, double bin_m = 0.02);

  /// Highest z of an upward triangle containing (x, y) in projection; nullopt if none.
  std::optional<double> height(double x_m, double y_m) const;

 private:
  const SurfaceMesh& mesh_;
  std::vector<std::size_t> upward_;
  double x0_ = 0, y0_ = 0, bin_m_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::size_t>> bins_;
};

/// A fresh empty directory under the system temp dir, named after the running test.
std::string freshTempDir(const std::string& name);

/// freshTempDir, removed with its contents when the object goes.
struct ScopedTempDir {
  explicit ScopedTempDir(const std::string& name);
  ~ScopedTempDir();
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  const std::string path;
};

/// Whole file as bytes.
std::string readBytes(const std::string& path);

}  // namespace climbsim::surface::test
