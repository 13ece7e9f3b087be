// Bad scene files: each gives one ConfigError line naming the file, the line and the value.

#include <gtest/gtest.h>

#include <map>

#include "climbsim/errors.hpp"
#include "climbsim/wall/scene.hpp"
#include "scene_test_files.hpp"

namespace climbsim::scene {
namespace {

struct BadCase {
  const char* label;
  std::map<std::string, std::string> files;  ///< relative path -> contents; "top.xml" is loaded
  std::string where;                         ///< "<file>:<line>:" expected in the message
  std::vector<std::string> mentions;         ///< further substrings expected (attribute, value, problem)
};

const std::string kPly = testing::asPly(testing::square(1.0, 0.0));

std::vector<BadCase> badCases() {
  using testing::sceneXml;
  return {
      {"missing mesh file", {{"top.xml", sceneXml(" <part name=\"A\" attached_to=\"ROOT\"/>\n <part name=\"B\" file=\"meshes/none.ply\" attached_to=\"A\"/>\n")}},
       "top.xml:3:", {"file=\"meshes/none.ply\"", "no such file"}},
      {"missing nested file", {{"top.xml", sceneXml("<part name=\"W\" file=\"walls/none.xml\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:2:", {"file=\"walls/none.xml\"", "no such file"}},
      {"unknown tag", {{"top.xml", sceneXml("\n<light name=\"sun\"/>\n")}}, "top.xml:3:", {"<light>"}},
      {"unknown attribute", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\" colour=\"red\"/>\n")}},
       "top.xml:2:", {"colour=\"red\"", "unknown attribute"}},
      {"missing attached_to", {{"top.xml", sceneXml("<part name=\"A\"/>\n")}}, "top.xml:2:", {"attached_to", "missing"}},
      {"offset not a number", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\" offset=\"0 0 1,5 0 0 0\"/>\n")}},
       "top.xml:2:", {"offset=\"0 0 1,5 0 0 0\"", "'1,5'"}},
      {"offset too short", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\" offset=\"0 0 1 0 0\"/>\n")}},
       "top.xml:2:", {"offset=\"0 0 1 0 0\"", "got 5"}},
      {"offset nan", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\" offset=\"0 0 nan 0 0 0\"/>\n")}},
       "top.xml:2:", {"offset=\"0 0 nan 0 0 0\"", "'nan'"}},
      {"max_distance bad", {{"top.xml", sceneXml("<distance_sensor name=\"l\" attached_to=\"ROOT\" max_distance=\"4m\" scan_angle_range=\"240\" angular_resolution=\"1\"/>\n")}},
       "top.xml:2:", {"max_distance=\"4m\""}},
      {"max_distance negative", {{"top.xml", sceneXml("<distance_sensor name=\"l\" attached_to=\"ROOT\" max_distance=\"-4\" scan_angle_range=\"240\" angular_resolution=\"1\"/>\n")}},
       "top.xml:2:", {"max_distance=\"-4\"", "> 0"}},
      {"camera width", {{"top.xml", sceneXml("<camera name=\"c\" type=\"orthographic\" near_limit=\"0.1\" width=\"25.5\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:2:", {"width=\"25.5\""}},
      {"two parts with one full name",
       {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\"/>\n<part name=\"A\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:3:", {"the full name ROOT:A", "top.xml:2"}},
      {"offset far away", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\" offset=\"1e19 0 0 0 0 0\"/>\n")}},
       "top.xml:2:", {"offset=\"1e19 0 0 0 0 0\"", "1e5 m"}},
      {"max_distance huge", {{"top.xml", sceneXml("<distance_sensor name=\"l\" attached_to=\"ROOT\" max_distance=\"1e300\" scan_angle_range=\"240\" angular_resolution=\"1\"/>\n")}},
       "top.xml:2:", {"max_distance=\"1e300\"", "at most 1000"}},
      {"camera near_limit huge", {{"top.xml", sceneXml("<camera name=\"c\" type=\"orthographic\" near_limit=\"-1e200\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:2:", {"near_limit=\"-1e200\"", "within"}},
      {"camera type", {{"top.xml", sceneXml("<camera name=\"c\" type=\"perspective\" near_limit=\"0.1\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:2:", {"type=\"perspective\""}},
      {"attached_to names nothing", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\"/>\n<part name=\"B\" attached_to=\"BRIDGE\"/>\n")}},
       "top.xml:3:", {"attached_to=\"BRIDGE\"", "names no insertion point"}},
      {"full name names nothing", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"ROOT\"/>\n<part name=\"B\" attached_to=\"ROOT:A:C\"/>\n")}},
       "top.xml:3:", {"attached_to=\"ROOT:A:C\"", "names no insertion point"}},
      {"element attached to nothing", {{"top.xml", sceneXml("<element name=\"p\" type=\"3d Pose\" angle_type=\"rad\" attached_to=\"ROBOT\"/>\n")}},
       "top.xml:2:", {"attached_to=\"ROBOT\""}},
      {"cycle of parts", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"B\"/>\n<part name=\"B\" attached_to=\"A\"/>\n")}},
       "top.xml:2:", {"attached_to=\"B\"", "cycle of insertion points"}},
      {"part attached to itself", {{"top.xml", sceneXml("<part name=\"A\" attached_to=\"A\"/>\n")}},
       "top.xml:2:", {"attached_to=\"A\"", "cycle"}},
      {"files including each other",
       {{"top.xml", sceneXml("<part name=\"W\" file=\"a.xml\" attached_to=\"ROOT\"/>\n")},
        {"a.xml", sceneXml("\n<part name=\"X\" file=\"sub/b.xml\" attached_to=\"ROOT\"/>\n")},
        {"sub/b.xml", sceneXml("<part name=\"Y\" file=\"../a.xml\" attached_to=\"ROOT\"/>\n")}},
       "b.xml:2:", {"file=\"../a.xml\"", "cycle of insertion points"}},
      {"file including itself", {{"top.xml", sceneXml("<part name=\"W\" file=\"top.xml\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:2:", {"file=\"top.xml\"", "cycle"}},
      {"mesh assimp cannot read", {{"top.xml", sceneXml("<part name=\"A\" file=\"junk.ply\" attached_to=\"ROOT\"/>\n")}, {"junk.ply", "this is no mesh\n"}},
       "top.xml:2:", {"part \"A\"", "file=\"junk.ply\"", "assimp cannot read"}},
      {"empty mesh",
       {{"top.xml", sceneXml("<part name=\"A\" file=\"points.obj\" attached_to=\"ROOT\"/>\n")}, {"points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"}},
       "top.xml:2:", {"file=\"points.obj\"", "empty mesh"}},
      {"empty PLY",
       {{"top.xml", sceneXml("<part name=\"A\" file=\"none.ply\" attached_to=\"ROOT\"/>\n")},
        {"none.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 0\nproperty list uchar int vertex_indices\nend_header\n"}},
       "top.xml:2:", {"file=\"none.ply\"", "part \"A\""}},
      {"bad angle_type", {{"top.xml", sceneXml("<part name=\"R\" attached_to=\"ROOT\"/>\n<element name=\"p\" type=\"3d Pose\" angle_type=\"grad\" attached_to=\"R\"/>\n")}},
       "top.xml:3:", {"angle_type=\"grad\""}},
      {"bad switch_mode", {{"top.xml", sceneXml("<part name=\"R\" attached_to=\"ROOT\"/>\n<element name=\"s\" type=\"Switch\" switch_mode=\"-2\" attached_to=\"R\"/>\n")}},
       "top.xml:3:", {"switch_mode=\"-2\""}},
      {"unknown element type", {{"top.xml", sceneXml("<part name=\"R\" attached_to=\"ROOT\"/>\n<element name=\"s\" type=\"Slider\" attached_to=\"R\"/>\n")}},
       "top.xml:3:", {"type=\"Slider\""}},
      {"pose attribute on a switch", {{"top.xml", sceneXml("<part name=\"R\" attached_to=\"ROOT\"/>\n<element name=\"s\" type=\"Switch\" switch_mode=\"-3\" angle_type=\"rad\" attached_to=\"R\"/>\n")}},
       "top.xml:3:", {"angle_type=\"rad\"", "unknown attribute"}},
      {"two elements of one name", {{"top.xml", sceneXml("<part name=\"R\" attached_to=\"ROOT\"/>\n<element name=\"s\" type=\"Switch\" switch_mode=\"-3\" attached_to=\"R\"/>\n<element name=\"s\" type=\"Switch\" switch_mode=\"-1\" attached_to=\"R\"/>\n")}},
       "top.xml:4:", {"name=\"s\""}},
      {"pose element on ROOT", {{"top.xml", sceneXml("<element name=\"p\" type=\"3d Pose\" angle_type=\"rad\" attached_to=\"ROOT\"/>\n")}},
       "top.xml:2:", {"attached_to=\"ROOT\""}},
      {"part named with a colon", {{"top.xml", sceneXml("<part name=\"A:B\" attached_to=\"ROOT\"/>\n")}}, "top.xml:2:", {"name=\"A:B\""}},
      {"not well-formed XML", {{"top.xml", "<scene>\n<part name=\"A\" attached_to=\"ROOT\">\n</scene>\n"}}, "top.xml:", {"XML"}},
      {"wrong root tag", {{"top.xml", "<world>\n</world>\n"}}, "top.xml:1:", {"<world>"}},
      {"bad part in a nested file",
       {{"top.xml", sceneXml("<part name=\"W\" file=\"walls/w.xml\" attached_to=\"ROOT\"/>\n")},
        {"walls/w.xml", sceneXml("\n\n<part name=\"M\" file=\"m.ply\" attached_to=\"ROOT\" offset=\"0 0 0 0 0 x\"/>\n")},
        {"walls/m.ply", kPly}},
       "walls/w.xml:4:", {"offset=\"0 0 0 0 0 x\""}},
  };
}

TEST(SceneBadInput, EachProblemIsOneLineNamingFileLineAndValue) {
  for (const auto& c : badCases()) {
    testing::TempDir dir;
    for (const auto& [name, text] : c.files) dir.write(name, text);
    try {
      loadScene(dir / "top.xml");
      ADD_FAILURE() << c.label << ": loaded";
    } catch (const ConfigError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << c.label << ": " << message;
      EXPECT_NE(message.find(c.where), std::string::npos) << c.label << ": " << message;
      EXPECT_NE(message.find(dir.path().string()), std::string::npos) << c.label << ": names no file: " << message;
      for (const auto& m : c.mentions) EXPECT_NE(message.find(m), std::string::npos) << c.label << ": " << message;
    } catch (const std::exception& e) {
      ADD_FAILURE() << c.label << ": not a ConfigError: " << e.what();
    }
  }
}

TEST(SceneBadInput, AMissingSceneFileNamesIt) {
  testing::TempDir dir;
  try {
    loadScene(dir / "none.xml");
    FAIL() << "loaded";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(dir / "none.xml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace climbsim::scene
