#include "climbsim/wall_patches/patch_spec.hpp"

#include <cmath>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::surface {
namespace {

class Checker {
 public:
  explicit Checker(const KeyLocator& where) : where_(where) {}

  void require(bool ok, const std::string& key, double value, const std::string& problem) const {
    if (ok && std::isfinite(value)) return;
    std::ostringstream line;
    line << where_(key) << ": " << key << " = " << value << ": " << (std::isfinite(value) ? problem : "not finite");
    throw ConfigError(line.str());
  }

 private:
  const KeyLocator& where_;
};

void checkLinear(const Checker& c, const LinearFeature& f, const std::string& key, double size_m) {
  c.require(f.x_m >= 0.0 && f.x_m <= size_m, key + ".x_m", f.x_m, "must lie on the face [0, size_m]");
  c.require(f.y_m >= 0.0 && f.y_m <= size_m, key + ".y_m", f.y_m, "must lie on the face [0, size_m]");
  c.require(true, key + ".angle_deg", f.angle_deg, "");
  c.require(f.width_m > 0.0 && f.width_m <= size_m / 4.0, key + ".width_m", f.width_m, "must be > 0 and <= size_m / 4");
  c.require(f.depth_m > 0.0 && f.depth_m <= size_m / 2.0, key + ".depth_m", f.depth_m, "must be > 0 and <= size_m / 2");
  c.require(f.length_m >= 0.0, key + ".length_m", f.length_m, "must be >= 0 (0: across the face)");
}

}  // namespace

const char* profileName(Profile profile) {
  switch (profile) {
    case Profile::kRect: return "rect";
    case Profile::kV: return "v";
    case Profile::kU: return "u";
  }
  return "?";
}

void validatePatchSpec(const PatchSpec& spec, const KeyLocator& where) {
  const Checker c(where);
  c.require(spec.size_m > 0.0 && spec.size_m <= 100.0, "size_m", spec.size_m, "must be in (0, 100]");
  c.require(spec.grid_m > 0.0 && spec.grid_m <= spec.size_m / 2.0, "grid_m", spec.grid_m, "must be in (0, size_m / 2]");
  // A grid finer than this gives more than 2e7 triangles on one face.
  c.require(spec.size_m / spec.grid_m <= 3200.0, "grid_m", spec.grid_m, "too fine: size_m / grid_m must be <= 3200");
  c.require(spec.wall_run_m > 0.0 && spec.wall_run_m <= 0.01, "wall_run_m", spec.wall_run_m, "must be in (0, 0.01]");
  c.require(spec.rough.rms_m >= 0.0 && spec.rough.rms_m <= 0.1, "rough.rms_m", spec.rough.rms_m, "must be in [0, 0.1]");
  c.require(spec.rough.correlation_length_m >= 0.0 && spec.rough.correlation_length_m <= spec.size_m / 4.0,
            "rough.correlation_length_m", spec.rough.correlation_length_m, "must be in [0, size_m / 4]");
  // The Gaussian filter's kernel spans 3 correlation lengths in grid cells on each side.
  c.require(spec.rough.correlation_length_m <= 100.0 * spec.grid_m, "rough.correlation_length_m",
            spec.rough.correlation_length_m, "must be <= 100 grid_m");
  for (std::size_t i = 0; i < spec.cracks.size(); ++i)
    checkLinear(c, spec.cracks[i], "cracks[" + std::to_string(i) + "]", spec.size_m);
  for (std::size_t i = 0; i < spec.grooves.size(); ++i)
    checkLinear(c, spec.grooves[i], "grooves[" + std::to_string(i) + "]", spec.size_m);
  const CrackNetwork& n = spec.network;
  c.require(n.count >= 0 && n.count <= 1000, "crack_network.count", n.count, "must be in [0, 1000]");
  c.require(n.segments >= 1 && n.segments <= 1000, "crack_network.segments", n.segments, "must be in [1, 1000]");
  c.require(n.segment_length_m > 0.0 && n.segment_length_m <= spec.size_m, "crack_network.segment_length_m",
            n.segment_length_m, "must be in (0, size_m]");
  c.require(n.turn_deg >= 0.0 && n.turn_deg <= 180.0, "crack_network.turn_deg", n.turn_deg, "must be in [0, 180]");
  c.require(n.width_m > 0.0 && n.width_m <= spec.size_m / 4.0, "crack_network.width_m", n.width_m,
            "must be > 0 and <= size_m / 4");
  c.require(n.depth_m > 0.0 && n.depth_m <= spec.size_m / 2.0, "crack_network.depth_m", n.depth_m,
            "must be > 0 and <= size_m / 2");
  for (std::size_t i = 0; i < spec.holes.size(); ++i) {
    const Hole& h = spec.holes[i];
    const std::string key = "holes[" + std::to_string(i) + "]";
    c.require(h.diameter_m > 2.0 * spec.wall_run_m && h.diameter_m <= spec.size_m / 2.0, key + ".diameter_m",
              h.diameter_m, "must be > 2 wall_run_m and <= size_m / 2");
    const double r = h.diameter_m / 2.0;
    c.require(h.x_m >= r && h.x_m <= spec.size_m - r, key + ".x_m", h.x_m, "the hole must lie inside the face");
    c.require(h.y_m >= r && h.y_m <= spec.size_m - r, key + ".y_m", h.y_m, "the hole must lie inside the face");
    c.require(h.depth_m > 0.0 && h.depth_m <= spec.size_m / 2.0, key + ".depth_m", h.depth_m,
              "must be > 0 and <= size_m / 2");
  }
  for (std::size_t i = 0; i < spec.steps.size(); ++i) {
    const Step& s = spec.steps[i];
    const std::string key = "steps[" + std::to_string(i) + "]";
    c.require(s.x_m >= 0.0 && s.x_m <= spec.size_m, key + ".x_m", s.x_m, "must lie on the face [0, size_m]");
    c.require(s.y_m >= 0.0 && s.y_m <= spec.size_m, key + ".y_m", s.y_m, "must lie on the face [0, size_m]");
    c.require(true, key + ".angle_deg", s.angle_deg, "");
    c.require(s.height_m != 0.0 && std::abs(s.height_m) <= spec.size_m / 2.0, key + ".height_m", s.height_m,
              "must be non-zero and |height| <= size_m / 2");
  }
}

}  // namespace climbsim::surface
