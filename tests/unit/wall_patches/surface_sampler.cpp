#include "surface_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <unistd.h>

namespace climbsim::surface::test {

SurfaceSampler::SurfaceSampler(const SurfaceMesh& mesh, double bin_m) : mesh_(mesh), bin_m_(bin_m) {
  double x1 = -1e30, y1 = -1e30;
  x0_ = y0_ = 1e30;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = mesh.vertices_m[tri[0]].cast<double>(), b = mesh.vertices_m[tri[1]].cast<double>(),
                          c = mesh.vertices_m[tri[2]].cast<double>();
    if ((b - a).cross(c - a).z() <= 0.0) continue;
    upward_.push_back(t);
    for (const auto& p : {a, b, c}) {
      x0_ = std::min(x0_, p.x());
      y0_ = std::min(y0_, p.y());
      x1 = std::max(x1, p.x());
      y1 = std::max(y1, p.y());
    }
  }
  nx_ = std::max(1, static_cast<int>(std::ceil((x1 - x0_) / bin_m_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((y1 - y0_) / bin_m_)) + 1);
  bins_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  for (std::size_t t : upward_) {
    const auto& tri = mesh.triangles[t];
    double lx = 1e30, ly = 1e30, hx = -1e30, hy = -1e30;
    for (int k = 0; k < 3; ++k) {
      lx = std::min<double>(lx, mesh.vertices_m[tri[k]].x());
      ly = std::min<double>(ly, mesh.vertices_m[tri[k]].y());
      hx = std::max<double>(hx, mesh.vertices_m[tri[k]].x());
      hy = std::max<double>(hy, mesh.vertices_m[tri[k]].y());
    }
    for (int by = static_cast<int>((ly - y0_) / bin_m_); by <= static_cast<int>((hy - y0_) / bin_m_); ++by)
      for (int bx = static_cast<int>((lx - x0_) / bin_m_); bx <= static_cast<int>((hx - x0_) / bin_m_); ++bx)
        bins_[static_cast<std::size_t>(by) * nx_ + bx].push_back(t);
  }
}

std::optional<double> SurfaceSampler::height(double x_m, double y_m) const {
  const int bx = static_cast<int>((x_m - x0_) / bin_m_), by = static_cast<int>((y_m - y0_) / bin_m_);
  if (bx < 0 || by < 0 || bx >= nx_ || by >= ny_) return std::nullopt;
  std::optional<double> best;
  for (std::size_t t : bins_[static_cast<std::size_t>(by) * nx_ + bx]) {
    const auto& tri = mesh_.triangles[t];
    const Eigen::Vector3d a = mesh_.vertices_m[tri[0]].cast<double>(), b = mesh_.vertices_m[tri[1]].cast<double>(),
                          c = mesh_.vertices_m[tri[2]].cast<double>();
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    const double wa = ((b.x() - x_m) * (c.y() - y_m) - (c.x() - x_m) * (b.y() - y_m)) / area;
    const double wb = ((c.x() - x_m) * (a.y() - y_m) - (a.x() - x_m) * (c.y() - y_m)) / area;
    const double wc = 1.0 - wa - wb;
    const double tolerance = -1e-9;
    if (wa < tolerance || wb < tolerance || wc < tolerance) continue;
    const double z = wa * a.z() + wb * b.z() + wc * c.z();
    if (!best || z > *best) best = z;
  }
  return best;
}

std::string freshTempDir(const std::string& name) {
  // Named after the running test and the process, so that ctest -j never shares one.
  std::string test = "outside_a_test";
  if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
    test = std::string(info->test_suite_name()) + "." + info->name();
  std::replace(test.begin(), test.end(), '/', '_');
  const auto dir = std::filesystem::temp_directory_path() /
                   ("climbsim_surface_" + test + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

}  // namespace climbsim::surface::test

namespace climbsim::surface::test {

ScopedTempDir::ScopedTempDir(const std::string& name) : path(freshTempDir(name)) {}

ScopedTempDir::~ScopedTempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path, ignored);
}

}  // namespace climbsim::surface::test
