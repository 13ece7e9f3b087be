#pragma once
/// @file
/// Scene files and meshes written by the scene tests into a temporary directory.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace climbsim::scene::testing {

/// A fresh directory under the system's temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "climbsim-scene-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& relative) const { return (path_ / relative).string(); }

  /// Writes `text` to `relative` (directories created); returns the full path.
  std::string write(const std::string& relative, const std::string& text) const {
    const auto full = path_ / relative;
    std::filesystem::create_directories(full.parent_path());
    std::ofstream(full, std::ios::trunc) << text;
    return full.string();
  }

 private:
  std::filesystem::path path_;
};

/// A scene file from its inner lines.
inline std::string sceneXml(const std::string& body) { return "<scene>\n" + body + "</scene>\n"; }

/// Rotations about one axis, written out by hand, angles in radians.
inline Eigen::Matrix3d rotX(double a) {
  Eigen::Matrix3d m;
  m << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return m;
}
inline Eigen::Matrix3d rotY(double a) {
  Eigen::Matrix3d m;
  m << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return m;
}
inline Eigen::Matrix3d rotZ(double a) {
  Eigen::Matrix3d m;
  m << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return m;
}
inline double deg(double d) { return d * M_PI / 180.0; }

/// A 4x4 homogeneous transform from a rotation and a translation.
inline Eigen::Matrix4d homogeneous(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = r;
  m.topRightCorner<3, 1>() = t;
  return m;
}

/// A unit square [0,1]^2 at z = 0 as two triangles, and a tetrahedron with 4 triangles: the
/// vertex sets the mesh format tests compare against.
struct TestMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};
inline TestMesh tetrahedron() {
  return {{{0.0, 0.0, 0.0}, {1.5, 0.0, 0.0}, {0.0, 0.25, 0.0}, {0.0, 0.0, 2.0}},
          {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
}
/// A flat square of edge `edge_m` centred on the origin at height z_m (two triangles).
inline TestMesh square(double edge_m, double z_m) {
  const double h = edge_m / 2;
  return {{{-h, -h, z_m}, {h, -h, z_m}, {h, h, z_m}, {-h, h, z_m}}, {{0, 1, 2}, {0, 2, 3}}};
}

inline std::string asPly(const TestMesh& m) {
  std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(m.vertices.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : m.vertices) s += std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
  for (const auto& t : m.triangles) s += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  return s;
}
inline std::string asObj(const TestMesh& m) {
  std::string s = "# test mesh\n";
  for (const auto& v : m.vertices) s += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
  for (const auto& t : m.triangles) {
    s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  }
  return s;
}
inline std::string asStl(const TestMesh& m) {
  std::string s = "solid test\n";
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n =
        (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
    s += "facet normal " + std::to_string(n.x()) + " " + std::to_string(n.y()) + " " + std::to_string(n.z()) +
         "\n outer loop\n";
    for (int k : t) {
      const auto& v = m.vertices[k];
      s += "  vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
    }
    s += " endloop\nendfacet\n";
  }
  return s + "endsolid test\n";
}

}  // namespace climbsim::scene::testing
