/// climbsim-surface: wall patches (2 m cubes with one structured face) and the default
/// pylon scene (docs/scene-files.md#wall-patches, docs/scene-files.md#scene-xml).

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/yaml_fields.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/wall_patches/mesh_io.hpp"
#include "climbsim/wall_patches/patch_spec_yaml.hpp"
#include "climbsim/wall_patches/pylon_scene.hpp"
#include "climbsim/run_prep/run_scene.hpp"
#include "climbsim/wall_patches/wall_patch.hpp"

namespace {

constexpr const char* kSpecHelp = R"(
Patch spec (YAML, --spec; every key optional, unknown keys are errors):
  size_m: 2.0            cube edge [m]
  grid_m: 0.004          heightfield spacing of the structured face [m]
  wall_run_m: 0.0002     horizontal run of steep walls (rect profiles, holes, steps) [m]
  seed: 1
  rough: {rms_m: 0.001, correlation_length_m: 0.02}
  cracks:    [{x_m, y_m, angle_deg, width_m, depth_m, profile: rect|v|u, length_m}]
  grooves:   [{x_m, y_m, angle_deg, width_m, depth_m, profile: rect|v|u, length_m}]
  crack_network: {count, segments, segment_length_m, turn_deg, width_m, depth_m, profile}
  holes:     [{x_m, y_m, diameter_m, depth_m}]
  steps:     [{x_m, y_m, angle_deg, height_m}]
Defaults: x_m 1, y_m 1, angle_deg 0, width_m 0.01 (grooves 0.02), depth_m 0.01,
  profile rect, length_m 0; crack_network count 0, segments 6, segment_length_m 0.15,
  turn_deg 25 (sd of the turn per joint), width_m 0.004, depth_m 0.015, profile v;
  holes diameter_m 0.05, depth_m 0.03; steps height_m 0.01.
Profiles: rect (flat floor, walls over wall_run_m), v, u (elliptic, 8 pieces a side);
every profile breakpoint is a vertex line of the mesh, so widths and depths are exact.
Patch frame: face x, y in [0, size_m], z out of the wall, rough mean plane z = 0, back at
z = -size_m; angles from +x towards +y. length_m 0 = across the whole face. Depths are
below the local rough surface; a step raises the side left of its direction.
Feature options take key=value lists with the same keys, e.g.
  --crack x_m=1,y_m=0.7,angle_deg=0,width_m=0.01,depth_m=0.04,profile=rect
and are appended to the spec's lists; --seed, --grid, --rms, --corr override the spec.
Output format from the extension: .ply (binary, default), .stl, .obj, .gltf, .glb, .dae.
Bad input: one line naming the file or option, the key and the value; exit code 2.)";

constexpr const char* kPylonHelp = R"(
Writes DIR/pylon.xml (SIMVIS3D scene), DIR/walls/pylon_blocks.xml (nested, included by
pylon.xml as part PYLON) and DIR/meshes/*.ply; every mesh is read back with assimp.
WALL (file="", a pure frame) is the wall frame W: origin in the concrete's mean plane,
x horizontal, y up, z out of the wall; ROOT has z up, WALL at (0, 0, 6) with roll 90 deg.
3 x 4 blocks of 2 m, x -2..4 m, y -6..2 m in W; the middle column (x 0..2) carries, from
the top: a horizontal crack at y = 0.70 m (10 mm wide, 40 mm deep, rect), a crack
network, holes, a step and grooves; all blocks rough (1 mm RMS, 20 mm correlation).
ROBOT (a frame: the scene service hangs the run's robot body on it) hangs on WALL with
DEPTH_CAMERA (offset 0) and TCP (0 0 0.35) on it; robot_pose (3d Pose, rad) and
robot_switch (Switch) act on ROBOT. The depth camera has no size: it covers the run's
robot's view.)";

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-surface: wall patches with rough concrete, cracks, holes, steps and grooves, "
               "and the default bridge-pylon scene"};
  app.require_subcommand(1);
  app.footer("\n'climbsim-surface patch --help' and 'climbsim-surface pylon --help' describe the two commands.");

  CLI::App* patch = app.add_subcommand("patch", "write one wall patch (a cube with one structured face)");
  patch->footer(kSpecHelp);
  std::string spec_file, out_file = "patch.ply";
  std::uint64_t seed = 0;
  double grid_m = 0.0, rms_m = 0.0, corr_m = 0.0;
  std::vector<std::string> cracks, grooves, holes, steps;
  std::string network;
  patch->add_option("--spec", spec_file, "YAML patch spec (see below)")->check(CLI::ExistingFile);
  patch->add_option("--out", out_file, "mesh file to write; the extension picks the format")->capture_default_str();
  CLI::Option* seed_option = patch->add_option("--seed", seed, "random seed (overrides the spec's seed)");
  CLI::Option* grid_option = patch->add_option("--grid", grid_m, "grid spacing of the structured face [m] (overrides grid_m)");
  CLI::Option* rms_option = patch->add_option("--rms", rms_m, "RMS roughness [m] (overrides rough.rms_m)");
  CLI::Option* corr_option = patch->add_option("--corr", corr_m, "correlation length [m] (overrides rough.correlation_length_m)");
  patch->add_option("--crack", cracks, "straight crack: x_m=,y_m=,angle_deg=,width_m=,depth_m=,profile=,length_m=");
  patch->add_option("--groove", grooves, "groove: same keys as --crack (default width_m 0.02)");
  patch->add_option("--network", network,
                    "crack network: count=,segments=,segment_length_m=,turn_deg=,width_m=,depth_m=,profile=");
  patch->add_option("--hole", holes, "hole: x_m=,y_m=,diameter_m=,depth_m=");
  patch->add_option("--step", steps, "step: x_m=,y_m=,angle_deg=,height_m=");

  CLI::App* pylon = app.add_subcommand("pylon", "write the default bridge-pylon scene: DIR/pylon.xml, "
                                                "DIR/walls/pylon_blocks.xml and DIR/meshes/*.ply");
  pylon->footer(kPylonHelp);
  std::string out_dir;
  std::uint64_t pylon_seed = surface::kPylonSeed;
  pylon->add_option("--out", out_dir, "scene directory")->required();
  pylon->add_option("--seed", pylon_seed, "random seed")->capture_default_str();
  surface::PylonCrack crack;
  pylon->add_option("--crack-depth-m", crack.depth_m,
                    "depth of the crack crack-descent drives over (block C1_R0, y = 0.70 m in W) [m]")
      ->capture_default_str();
  pylon->add_option("--crack-width-m", crack.width_m, "width of that crack [m]")->capture_default_str();

  return guardedMain(app, argc, argv, "surface", [&]() -> int {
    const auto start = std::chrono::steady_clock::now();
    const auto seconds = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    if (pylon->parsed()) {
      std::size_t total = 0;
      for (const surface::WrittenMesh& m : surface::writePylonScene(out_dir, pylon_seed, crack)) {
        spdlog::info("{}: {} triangles", m.path, m.triangles);
        total += m.triangles;
      }
      spdlog::info("{}/pylon.xml: {} triangles in all, {:.1f} s", out_dir, total, seconds());
      return kExitOk;
    }

    surface::PatchSpec spec;
    YAML::Node root;
    if (!spec_file.empty()) {
      root = YamlFields::loadFile(spec_file, "patch spec");
      surface::mergePatchSpec(spec, root, spec_file);
      surface::validatePatchSpecFrom(spec, root, spec_file);
    }
    if (seed_option->count() > 0) spec.seed = seed;
    if (grid_option->count() > 0) spec.grid_m = grid_m;
    if (rms_option->count() > 0) spec.rough.rms_m = rms_m;
    if (corr_option->count() > 0) spec.rough.correlation_length_m = corr_m;
    // Each option list becomes a YAML list, so it is read and checked like a spec file.
    const auto merge = [&](const std::vector<std::string>& texts, const char* key, const std::string& option) {
      for (const std::string& text : texts) {
        YAML::Node node(YAML::NodeType::Map);
        YAML::Node list(YAML::NodeType::Sequence);
        list.push_back(surface::keyValueList(text, option));
        node[key] = list;
        surface::mergePatchSpec(spec, node, option);
      }
    };
    merge(cracks, "cracks", "--crack");
    merge(grooves, "grooves", "--groove");
    merge(holes, "holes", "--hole");
    merge(steps, "steps", "--step");
    if (!network.empty()) {
      YAML::Node node(YAML::NodeType::Map);
      node["crack_network"] = surface::keyValueList(network, "--network");
      surface::mergePatchSpec(spec, node, "--network");
    }
    const auto from = [&](const char* option) {
      return spec_file.empty() ? std::string(option) : std::string(option) + " or " + spec_file;
    };
    surface::validatePatchSpec(spec, [&](const std::string& key) {
      if (key.rfind("cracks", 0) == 0 && !cracks.empty()) return from("--crack");
      if (key.rfind("grooves", 0) == 0 && !grooves.empty()) return from("--groove");
      if (key.rfind("holes", 0) == 0 && !holes.empty()) return from("--hole");
      if (key.rfind("steps", 0) == 0 && !steps.empty()) return from("--step");
      if (key.rfind("crack_network", 0) == 0 && !network.empty()) return std::string("--network");
      if (key == "grid_m" && grid_option->count() > 0) return std::string("--grid");
      if (key == "rough.rms_m" && rms_option->count() > 0) return std::string("--rms");
      if (key == "rough.correlation_length_m" && corr_option->count() > 0) return std::string("--corr");
      return spec_file.empty() ? std::string("defaults") : spec_file;
    });
    surface::exportFormatFor(out_file);
    const surface::WallPatch result = surface::generateWallPatch(spec);
    surface::writeMeshChecked(out_file, result.mesh);
    spdlog::info("{}: {} triangles ({} on the structured face, grid {} x {} cells of {} mm), {:.2f} s", out_file,
                 result.mesh.triangles.size(), result.face_triangles, result.grid_cells, result.grid_cells,
                 result.grid_spacing_m * 1e3, seconds());
    return kExitOk;
  });
}
