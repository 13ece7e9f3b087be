// YamlFields and YamlMap, the one mechanism every YAML file of climbsim is read with (scenario,
// compose, robot, patch spec): one line per problem, "<file>:<line>: <key> = <value>: <why>",
// every problem of a file at once, in line order.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim {
namespace {

/// The message of the ConfigError `body` throws ("" if none).
template <typename Body>
std::string errorOf(Body&& body) {
  try {
    body();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(YamlFields, RequiredNamesTheMissingKeyAtItsMapsLineAndNeverInserts) {
  const YAML::Node root = YamlFields::load("a: 1\nsection:\n  x: 2\n", "f.yaml");
  const YamlFields f("f.yaml");
  EXPECT_EQ(f.required(root["section"], "section", "x").as<int>(), 2);
  EXPECT_EQ(errorOf([&] { f.required(root["section"], "section", "y"); }), "f.yaml:3: section.y: missing");
  EXPECT_EQ(errorOf([&] { f.required(root, "", "b"); }), "f.yaml:1: b: missing");
  EXPECT_FALSE(root["section"]["y"].IsDefined());
  EXPECT_EQ(root["section"].size(), 1u);
}

TEST(YamlFields, FailValueShowsAValueWithoutANode) {
  const YamlFields f("scenario --set");
  EXPECT_EQ(errorOf([&] { f.failValue(0, "body.mass_kg", "-1", "must be in (0, 10000]"); }),
            "scenario --set: body.mass_kg = -1: must be in (0, 10000]");
  const YamlFields g("r.yaml");
  EXPECT_EQ(errorOf([&] { g.failValue(7, "k", "a\nb", "why"); }), "r.yaml:7: k = a\\nb: why");
}

TEST(YamlFields, RequireMapWithAKeyListRecordsEveryUnknownKeyAndSaysWhetherAllWereKnown) {
  const YAML::Node root = YamlFields::load("a: 1\nzz: 2\nb: 3\nyy: 4\n", "m.yaml");
  const YamlFields f("m.yaml");
  EXPECT_FALSE(f.requireMap(root, "top", std::vector<std::string>{"a", "b"}));
  const std::string message = errorOf([&] { f.finish(); });
  const auto all = lines(message);
  ASSERT_EQ(all.size(), 2u) << message;
  EXPECT_EQ(all[0], "m.yaml:2: top.zz: unknown key (known keys: a, b)");
  EXPECT_EQ(all[1], "m.yaml:4: top.yy: unknown key (known keys: a, b)");
  const YamlFields ok("m.yaml");
  EXPECT_TRUE(ok.requireMap(root, "top", std::vector<std::string>{"a", "b", "zz", "yy"}));
  EXPECT_FALSE(ok.failed());
}

TEST(YamlFields, LoadFileNamesAnUnreadableFileAndASyntaxErrorsLine) {
  EXPECT_EQ(errorOf([] { YamlFields::loadFile("/nonexistent/robot.yaml", "robot description"); }),
            "/nonexistent/robot.yaml: cannot read the robot description");
  const std::string path = ::testing::TempDir() + "yaml_fields_broken.yaml";
  std::ofstream(path) << "a: 1\nb: [2\n";
  const std::string message = errorOf([&] { YamlFields::loadFile(path, "thing"); });
  EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
  std::remove(path.c_str());
}

TEST(YamlMap, ReadsTakenKeysKeepsAbsentOnesAndReportsEveryProblemInLineOrder) {
  const YAML::Node root = YamlFields::load(
      "name: pylon\n"
      "count: 2.5\n"
      "size_m: 3\n"
      "typo_m: 1\n"
      "on: maybe\n"
      "width_m: wide\n",
      "s.yaml");
  const YamlFields f("s.yaml");
  YamlMap map(f, root, "");
  std::string name;
  int count = 7;
  double size = 0.0, width = 0.5, depth = 0.25;
  bool on = false;
  EXPECT_TRUE(map.text("name", name));
  EXPECT_FALSE(map.integer("count", count, 0, 10));
  EXPECT_TRUE(map.number("size_m", size));
  EXPECT_FALSE(map.boolean("on", on));
  EXPECT_FALSE(map.number("width_m", width));
  EXPECT_TRUE(map.number("depth_m", depth));  // absent: kept
  map.rejectUnknown();
  EXPECT_EQ(name, "pylon");
  EXPECT_EQ(size, 3.0);
  EXPECT_EQ(count, 7);    // unchanged by a bad value
  EXPECT_EQ(width, 0.5);  // idem
  EXPECT_EQ(depth, 0.25);
  const std::string message = errorOf([&] { f.finish(); });
  const auto all = lines(message);
  ASSERT_EQ(all.size(), 4u) << message;
  EXPECT_EQ(all[0], "s.yaml:2: count = 2.5: it must be an integer in 0..10");
  EXPECT_EQ(all[1].rfind("s.yaml:4: typo_m: unknown key (known keys: name, count, size_m, on, width_m, depth_m)", 0), 0u)
      << all[1];
  EXPECT_EQ(all[2], "s.yaml:5: on = maybe: it must be true or false");
  EXPECT_EQ(all[3], "s.yaml:6: width_m = wide: it must be a finite number");
}

TEST(YamlMap, ANestedMapNamesItsPathAndANonMapIsRefused) {
  const YAML::Node root = YamlFields::load("rough:\n  rms_m: x\nlist: [1, 2]\n", "p.yaml");
  const YamlFields f("p.yaml");
  YamlMap rough(f, root["rough"], "rough");
  double rms = 0.0;
  rough.number("rms_m", rms);
  EXPECT_EQ(errorOf([&] { f.finish(); }), "p.yaml:2: rough.rms_m = x: it must be a finite number");
  EXPECT_NE(errorOf([&] { YamlMap(f, root["list"], "list"); }).find("p.yaml:3: list = [1, 2]: it must be a mapping"),
            std::string::npos);
}

}  // namespace
}  // namespace climbsim
