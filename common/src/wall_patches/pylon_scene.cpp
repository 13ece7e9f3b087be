#include "climbsim/wall_patches/pylon_scene.hpp"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include <tinyxml2.h>

#include "climbsim/errors.hpp"
#include "climbsim/wall_patches/mesh_io.hpp"
#include "climbsim/wall_patches/seeded_random.hpp"
#include "climbsim/wall_patches/wall_patch.hpp"

namespace climbsim::surface {
namespace {

constexpr double kBlockM = 2.0;
constexpr int kColumns = 3;
constexpr int kRows = 4;
constexpr int kPathColumn = 1;
constexpr std::uint64_t kBlockStreamBase = 100;

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string offset(double x, double y, double z, double roll_deg, double pitch_deg, double yaw_deg) {
  std::ostringstream out;
  out << formatNumber(x) << ' ' << formatNumber(y) << ' ' << formatNumber(z) << ' ' << formatNumber(roll_deg) << ' '
      << formatNumber(pitch_deg) << ' ' << formatNumber(yaw_deg);
  return out.str();
}

tinyxml2::XMLElement* addPart(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* scene, const std::string& file,
                              const std::string& name, const std::string& attached_to, const std::string& offset_text) {
  tinyxml2::XMLElement* part = doc.NewElement("part");
  part->SetAttribute("file", file.c_str());
  part->SetAttribute("name", name.c_str());
  part->SetAttribute("attached_to", attached_to.c_str());
  part->SetAttribute("offset", offset_text.c_str());
  scene->InsertEndChild(part);
  return part;
}

void save(tinyxml2::XMLDocument& doc, const std::string& path) {
  if (doc.SaveFile(path.c_str()) != tinyxml2::XML_SUCCESS) throw ConfigError(path + ": cannot write the scene file");
}

PatchSpec roughBlock(std::uint64_t seed, double grid_m) {
  PatchSpec spec;
  spec.size_m = kBlockM;
  spec.grid_m = grid_m;
  spec.seed = seed;
  spec.rough.rms_m = 0.001;
  spec.rough.correlation_length_m = 0.02;
  return spec;
}

}  // namespace

/// `metres` in millimetres, shortest form ("10", "12.5").
static std::string millimetres(double metres) {
  std::ostringstream out;
  out << metres * 1000.0;
  return out.str();
}

std::vector<PylonBlock> defaultPylonBlocks(std::uint64_t seed, const PylonCrack& pylon_crack) {
  std::vector<PylonBlock> blocks;
  for (int row = 0; row < kRows; ++row)
    for (int column = 0; column < kColumns; ++column) {
      PylonBlock b;
      b.column = column;
      b.row = row;
      b.x_m = -kBlockM + kBlockM * column;
      b.y_m = -kBlockM * row;
      const std::uint64_t block_seed = deriveSeed(seed, kBlockStreamBase + static_cast<std::uint64_t>(blocks.size()));
      const bool path = column == kPathColumn;
      b.spec = roughBlock(block_seed, path ? 0.005 : 0.010);
      b.kind = "rough";
      if (path && row == 0) {
        b.kind = "crack";
        LinearFeature crack;
        crack.x_m = 1.0;
        crack.y_m = 0.70;  // W y = 0.70: 0.50 m below the scenario's start at y = 1.2
        crack.angle_deg = 0.0;
        crack.width_m = pylon_crack.width_m;
        crack.depth_m = pylon_crack.depth_m;
        crack.profile = Profile::kRect;
        b.spec.cracks.push_back(crack);
      } else if (path && row == 1) {
        b.kind = "network";
        b.spec.network.count = 5;
        b.spec.network.segments = 8;
        b.spec.network.segment_length_m = 0.2;
        b.spec.network.turn_deg = 25.0;
        b.spec.network.width_m = 0.004;
        b.spec.network.depth_m = 0.015;
        b.spec.network.profile = Profile::kV;
      } else if (path && row == 2) {
        b.kind = "holes";
        const double holes[][4] = {{0.6, 1.5, 0.020, 0.020}, {1.0, 1.0, 0.050, 0.030}, {1.4, 0.5, 0.100, 0.050},
                                   {0.5, 0.4, 0.030, 0.060}, {1.5, 1.6, 0.012, 0.080}};
        for (const auto& h : holes) b.spec.holes.push_back(Hole{h[0], h[1], h[2], h[3]});
      } else if (path && row == 3) {
        b.kind = "step_groove";
        b.spec.steps.push_back(Step{1.0, 1.4, 0.0, 0.015});  // the part above y = 1.4 stands 15 mm proud
        LinearFeature across;
        across.x_m = 1.0;
        across.y_m = 0.7;
        across.angle_deg = 0.0;
        across.width_m = 0.030;
        across.depth_m = 0.010;
        across.profile = Profile::kU;
        b.spec.grooves.push_back(across);
        LinearFeature along;
        along.x_m = 0.5;
        along.y_m = 0.7;
        along.angle_deg = 90.0;
        along.width_m = 0.020;
        along.depth_m = 0.015;
        along.length_m = 1.0;
        along.profile = Profile::kRect;
        b.spec.grooves.push_back(along);
      }
      if (column == kColumns - 1) b.yaw_deg = 180.0;
      b.name = "BLOCK_C" + std::to_string(column) + "_R" + std::to_string(row);
      b.mesh = "block_c" + std::to_string(column) + "_r" + std::to_string(row) + "_" + b.kind + ".ply";
      blocks.push_back(b);
    }
  return blocks;
}

std::vector<WrittenMesh> writePylonScene(const std::string& dir, std::uint64_t seed, const PylonCrack& crack) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(fs::path(dir) / "meshes", error);
  if (!error) fs::create_directories(fs::path(dir) / "walls", error);
  if (error) throw ConfigError(dir + ": cannot create the scene directory: " + error.message());

  std::vector<WrittenMesh> written;
  const std::vector<PylonBlock> blocks = defaultPylonBlocks(seed, crack);
  for (const PylonBlock& b : blocks) {
    validatePatchSpec(b.spec, [&](const std::string&) { return "pylon block " + b.name; });
    const WallPatch patch = generateWallPatch(b.spec);
    const std::string path = (fs::path(dir) / "meshes" / b.mesh).string();
    writeMeshChecked(path, patch.mesh);
    written.push_back({path, patch.mesh.triangles.size()});
  }

  {
    tinyxml2::XMLDocument doc;
    const std::string comment =
        " The blocks of the default pylon (generated by climbsim-surface pylon, seed " + std::to_string(seed) +
        "). ROOT here is the part that includes this file (WALL: the wall frame W, z out of the wall,\n"
        "     y up). Each block is a 2 m cube whose structured face lies in its z = 0 plane, facing +z. ";
    doc.InsertEndChild(doc.NewComment(comment.c_str()));
    tinyxml2::XMLElement* scene = doc.NewElement("scene");
    doc.InsertEndChild(scene);
    for (const PylonBlock& b : blocks) {
      // Yaw 180 about the block's z turns the face in place when the corner moves by (2, 2).
      const bool turned = b.yaw_deg != 0.0;
      addPart(doc, scene, "../meshes/" + b.mesh, b.name, "ROOT",
              offset(b.x_m + (turned ? kBlockM : 0.0), b.y_m + (turned ? kBlockM : 0.0), 0.0, 0.0, 0.0, b.yaw_deg));
    }
    save(doc, (fs::path(dir) / "walls" / "pylon_blocks.xml").string());
  }
  {
    tinyxml2::XMLDocument doc;
    const std::string comment =
        " Default scene: a bridge pylon and the robot (generated by climbsim-surface pylon, seed " +
        std::to_string(seed) +
        ").\n"
        "     WALL is the wall frame W: origin in the mean plane of the concrete, x horizontal, y up, z out of\n"
        "     the wall; here 6 m above the ground with ROOT z up. Blocks: x -2..4 m, y -6..2 m in W.\n"
        "     Horizontal crack (" + millimetres(crack.width_m) + " mm wide, " + millimetres(crack.depth_m) +
        " mm deep) at y = 0.70 m in W, across x 0..2 m, 0.5 m below the\n"
        "     crack-descent start (x 1.0, y 1.2). Parts with file=\"\" are pure insertion points (frames);\n"
        "     the scene service hangs the run's robot body (from its robot file) under ROBOT. ";
    doc.InsertEndChild(doc.NewComment(comment.c_str()));
    tinyxml2::XMLElement* scene = doc.NewElement("scene");
    doc.InsertEndChild(scene);
    addPart(doc, scene, "", "WALL", "ROOT", offset(0, 0, 6, 90, 0, 0));
    addPart(doc, scene, "walls/pylon_blocks.xml", "PYLON", "WALL", offset(0, 0, 0, 0, 0, 0));
    addPart(doc, scene, "", "ROBOT", "WALL", offset(0, 0, 0, 0, 0, 0));
    addPart(doc, scene, "", "DEPTH_CAMERA", "ROBOT", offset(0, 0, 0, 0, 0, 0));
    addPart(doc, scene, "", "TCP", "ROBOT", offset(0, 0, 0.35, 0, 0, 0));

    tinyxml2::XMLElement* pose = doc.NewElement("element");
    pose->SetAttribute("name", "robot_pose");
    pose->SetAttribute("type", "3d Pose");
    pose->SetAttribute("angle_type", "rad");
    pose->SetAttribute("attached_to", "ROBOT");
    scene->InsertEndChild(pose);
    tinyxml2::XMLElement* sw = doc.NewElement("element");
    sw->SetAttribute("name", "robot_switch");
    sw->SetAttribute("type", "Switch");
    sw->SetAttribute("switch_mode", "-3");
    sw->SetAttribute("attached_to", "ROBOT");
    scene->InsertEndChild(sw);
    tinyxml2::XMLElement* laser = doc.NewElement("distance_sensor");
    laser->SetAttribute("name", "laser_scanner");
    laser->SetAttribute("max_distance", "4");
    laser->SetAttribute("scan_angle_range", "240");
    laser->SetAttribute("angular_resolution", "0.352423");
    laser->SetAttribute("offset", offset(0, 0, 0, 0, 20, 0).c_str());
    laser->SetAttribute("attached_to", "TCP");
    scene->InsertEndChild(laser);
    tinyxml2::XMLElement* camera = doc.NewElement("camera");
    camera->SetAttribute("name", "depth_cam");
    camera->SetAttribute("type", "orthographic");
    // Distances along the view direction (-z of DEPTH_CAMERA, the sealing plane): heights
    // +0.05 m .. -0.05 m about the sealing plane.
    camera->SetAttribute("near_limit", "-0.05");
    camera->SetAttribute("far_limit", "0.05");
    camera->SetAttribute("width", "256");
    camera->SetAttribute("height", "256");
    // No size: the image covers the run's robot's view (climbsim/robot/depth_view.hpp).
    camera->SetAttribute("attached_to", "DEPTH_CAMERA");
    scene->InsertEndChild(camera);
    save(doc, (fs::path(dir) / "pylon.xml").string());
  }
  return written;
}

}  // namespace climbsim::surface
