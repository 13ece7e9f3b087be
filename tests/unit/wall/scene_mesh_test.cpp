// Mesh files through assimp: every format the scene supports, node hierarchies, switches.

#include <gtest/gtest.h>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <memory>

#include "climbsim/errors.hpp"
#include "climbsim/wall/mesh_file.hpp"
#include "climbsim/wall/scene.hpp"
#include "scene_test_files.hpp"

namespace climbsim::scene {
namespace {

using Triangle = std::array<Eigen::Vector3d, 3>;

std::vector<Triangle> expectedTriangles(const testing::TestMesh& mesh, const Eigen::Matrix4d& transform) {
  std::vector<Triangle> out;
  for (const auto& t : mesh.triangles) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) tri[k] = (transform * mesh.vertices[t[k]].homogeneous()).head<3>();
    out.push_back(tri);
  }
  return out;
}

/// Every expected triangle is in `mesh` (same corners, same winding up to rotation), and
/// the counts agree.
void expectSameTriangles(const LocalMesh& mesh, const std::vector<Triangle>& expected, const std::string& what) {
  ASSERT_EQ(mesh.triangles.size(), expected.size()) << what;
  std::vector<bool> used(mesh.triangles.size(), false);
  for (const auto& want : expected) {
    bool found = false;
    for (std::size_t i = 0; i < mesh.triangles.size() && !found; ++i) {
      if (used[i]) continue;
      for (int rotation = 0; rotation < 3 && !found; ++rotation) {
        bool all = true;
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d got = mesh.vertices_m[mesh.triangles[i][(k + rotation) % 3]].cast<double>();
          all = all && (got - want[k]).norm() < 1e-5;
        }
        found = all;
      }
      if (found) used[i] = true;
    }
    EXPECT_TRUE(found) << what << ": no triangle (" << want[0].transpose() << "), (" << want[1].transpose() << "), ("
                       << want[2].transpose() << ")";
  }
}

/// Exports the OBJ file `obj` with assimp into `format` (an assimp exporter id) at `out`,
/// after putting its nodes below a parent with transform `outer` and giving the old root
/// `inner` (pre-multiplied): the vertices then sit at outer * inner * v.
void exportWithHierarchy(const std::string& obj, const std::string& format, const std::string& out,
                         const Eigen::Matrix4d& outer, const Eigen::Matrix4d& inner) {
  Assimp::Importer importer;
  ASSERT_NE(importer.ReadFile(obj, 0), nullptr) << importer.GetErrorString();
  std::unique_ptr<aiScene> scene(importer.GetOrphanedScene());
  auto toAi = [](const Eigen::Matrix4d& m) {
    return aiMatrix4x4(m(0, 0), m(0, 1), m(0, 2), m(0, 3), m(1, 0), m(1, 1), m(1, 2), m(1, 3), m(2, 0), m(2, 1),
                       m(2, 2), m(2, 3), m(3, 0), m(3, 1), m(3, 2), m(3, 3));
  };
  aiNode* old_root = scene->mRootNode;
  old_root->mTransformation = toAi(inner) * old_root->mTransformation;
  auto* root = new aiNode("outer");
  root->mTransformation = toAi(outer);
  root->mNumChildren = 1;
  root->mChildren = new aiNode*[1]{old_root};
  old_root->mParent = root;
  scene->mRootNode = root;
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(scene.get(), format, out), AI_SUCCESS) << format << ": " << exporter.GetErrorString();
}

TEST(SceneMesh, EveryFormatLoadsWithItsTrianglesAndVertexPositions) {
  testing::TempDir dir;
  const auto tetra = testing::tetrahedron();
  const auto identity = expectedTriangles(tetra, Eigen::Matrix4d::Identity());
  expectSameTriangles(loadMeshFile(dir.write("t.ply", testing::asPly(tetra)), "test", "ply"), identity, "PLY ascii");
  const auto obj = dir.write("t.obj", testing::asObj(tetra));
  expectSameTriangles(loadMeshFile(obj, "test", "obj"), identity, "OBJ");
  expectSameTriangles(loadMeshFile(dir.write("t.stl", testing::asStl(tetra)), "test", "stl"), identity, "STL ascii");

  // The rest written by assimp's exporter, each with a two-level node hierarchy whose
  // transforms the loader must apply.
  const Eigen::Matrix4d outer = testing::homogeneous(testing::rotZ(testing::deg(90)), {1.0, 2.0, 3.0});
  const Eigen::Matrix4d inner = testing::homogeneous(testing::rotX(testing::deg(30)), {0.0, 0.0, -0.5});
  const auto moved = expectedTriangles(tetra, outer * inner);
  struct Format {
    const char* id;
    const char* file;
    bool keeps_hierarchy;  ///< STL and PLY have no nodes: the exporter bakes the transforms in
  };
  for (const Format& f : {Format{"plyb", "t_bin.ply", false}, Format{"stlb", "t_bin.stl", false},
                          Format{"gltf2", "t.gltf", true}, Format{"glb2", "t.glb", true},
                          Format{"collada", "t.dae", true}, Format{"obj", "t_exported.obj", false}}) {
    const std::string path = dir / f.file;
    exportWithHierarchy(obj, f.id, path, outer, inner);
    expectSameTriangles(loadMeshFile(path, "test", f.file), moved, f.id);
  }
}

TEST(SceneMesh, SwitchingOffRemovesTheTrianglesOfTheWholeSubtree) {
  testing::TempDir dir;
  dir.write("square.ply", testing::asPly(testing::square(1.0, 0.0)));
  dir.write("tetra.obj", testing::asObj(testing::tetrahedron()));
  const auto file = dir.write("s.xml", testing::sceneXml(R"(
  <part name="WALL" file="square.ply" attached_to="ROOT"/>
  <part name="BLOCK" file="tetra.obj" attached_to="WALL" offset="0 0 1 0 0 0"/>
  <part name="BLOCK_TOP" file="square.ply" attached_to="BLOCK" offset="0 0 2 0 0 0"/>
  <part name="ROBOT" file="square.ply" attached_to="WALL"/>
  <part name="WHEEL" file="tetra.obj" attached_to="ROBOT"/>
  <element name="robot_pose" type="3d Pose" angle_type="rad" attached_to="ROBOT"/>
  <element name="blocks" type="Switch" switch_mode="-3" attached_to="BLOCK"/>
  <element name="robot" type="Switch" switch_mode="-1" attached_to="ROBOT"/>
)"));
  Scene scene = loadScene(file);
  auto count = [&](const TriangleMesh& mesh, const std::string& part) {
    const auto id = scene.partIndex(part);
    return std::count(mesh.part_ids.begin(), mesh.part_ids.end(), id);
  };
  // WALL 2 + BLOCK 4 + BLOCK_TOP 2 static; the robot starts switched off.
  EXPECT_EQ(scene.staticMesh().triangles.size(), 8u);
  EXPECT_EQ(scene.staticMesh().part_ids.size(), 8u);
  EXPECT_EQ(count(scene.staticMesh(), "BLOCK"), 4);
  EXPECT_TRUE(scene.movingMesh().triangles.empty());

  scene.setSwitch("blocks", false);
  EXPECT_EQ(scene.staticMesh().triangles.size(), 2u);
  EXPECT_EQ(count(scene.staticMesh(), "WALL"), 2);
  scene.setSwitch("robot", true);
  const auto moving = scene.movingMesh();
  EXPECT_EQ(moving.triangles.size(), 6u);
  EXPECT_EQ(count(moving, "WHEEL"), 4);
  EXPECT_EQ(scene.worldMesh().triangles.size(), 8u);
  scene.setSwitch("blocks", true);
  EXPECT_EQ(scene.worldMesh().triangles.size(), 14u);
  EXPECT_THROW(scene.setSwitch("nope", true), ConfigError);
}

}  // namespace
}  // namespace climbsim::scene
