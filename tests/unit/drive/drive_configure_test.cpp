// climbsim-drive's one configuration path (services/drive/configure.hpp): the service's main
// loads the scenario from its command line, climbsim solo from the run directory; both hand it
// to configureDrive and get the same setup, whose values are the scenario's and the robot's.
// Each command-line option changes the one value it names.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "drive/configure.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;
const std::string kBuild = "/the/build";

/// The names of the setup's values that differ between a and b.
std::vector<std::string> differences(const DriveSetup& a, const DriveSetup& b) {
  std::vector<std::string> out;
  auto note = [&](const char* name, bool same) {
    if (!same) out.push_back(name);
  };
  note("start.x_m", a.start.x_m == b.start.x_m);
  note("start.y_m", a.start.y_m == b.start.y_m);
  note("start.yaw_rad", a.start.yaw_rad == b.start.yaw_rad);
  note("wall", a.wall.gravity_x == b.wall.gravity_x && a.wall.gravity_y == b.wall.gravity_y &&
                   a.wall.gravity_z == b.wall.gravity_z);
  note("params.substep_s", a.params.substep_s == b.params.substep_s);
  note("params.contact_backend", a.params.contact_backend == b.params.contact_backend);
  note("params.mass_kg", a.params.mass_kg == b.params.mass_kg);
  note("params.wheels", a.params.wheels.size() == b.params.wheels.size());
  note("hold_until_ns", a.hold_until_ns == b.hold_until_ns);
  note("downforce_n", a.downforce_n == b.downforce_n);
  note("inputs", a.inputs.command == b.inputs.command && a.inputs.adhesion == b.inputs.adhesion);
  note("end_on_fall", a.end_on_fall == b.end_on_fall);
  note("scene_file", a.scene_file == b.scene_file);
  note("params.ground", (a.params.ground == nullptr) == (b.params.ground == nullptr));
  return out;
}

TEST(DriveConfigure, MainAndSoloGetTheSameSetupFromAScenario) {
  for (const char* name : {"crack-descent", "overhang", "climb-up"}) {
    const std::string file = kScenarios + "/" + name + ".yaml";
    const DriveSetup main_setup = configureDrive(loadScenarioAndRobot(file, {}), {}, kBuild);
    const DriveSetup solo_setup = configureDrive(scenarioAndRobot(loadScenario(file)), {}, kBuild);
    EXPECT_EQ(differences(main_setup, solo_setup), std::vector<std::string>{}) << name;
  }
}

TEST(DriveConfigure, TheScenarioGivesStartWallSubstepHoldAndScene) {
  const ScenarioAndRobot run = loadScenarioAndRobot(kScenarios + "/overhang.yaml", {});
  const Scenario& s = *run.scenario;
  const DriveSetup setup = configureDrive(run, {}, kBuild);
  EXPECT_DOUBLE_EQ(setup.start.x_m, -1.0);
  EXPECT_DOUBLE_EQ(setup.start.y_m, s.start.y_m);
  EXPECT_DOUBLE_EQ(setup.start.yaw_rad, s.start.yaw_deg * M_PI / 180.0);
  const WallOrientation overhang = WallOrientation::overhang(30.0);
  EXPECT_DOUBLE_EQ(setup.wall.gravity_y, overhang.gravity_y);
  EXPECT_DOUBLE_EQ(setup.wall.gravity_z, overhang.gravity_z);
  EXPECT_DOUBLE_EQ(setup.params.substep_s, 1.0 / s.rates.drive_hz);
  EXPECT_EQ(setup.hold_until_ns, 2'000'000'000);
  EXPECT_EQ(setup.end_on_fall, s.end_on.fall);
  EXPECT_EQ(setup.scene_file, kBuild + "/scenes/pylon.xml");
  // thermo's AdhesionForce is read: F = 0 until its first sample (its initial state).
  EXPECT_EQ(setup.downforce_n, kAdhesionForceBeforeThermo_n);
  // The robot's parameters are the robot file's.
  const DriveParams robot = driveParamsFromRobot(run.robot, run.geometry);
  EXPECT_EQ(setup.params.mass_kg, robot.mass_kg);
  EXPECT_EQ(setup.params.wheels.size(), robot.wheels.size());
  EXPECT_EQ(setup.params.contact_backend, robot.contact_backend);
}

TEST(DriveConfigure, ASceneTheProcessReadAlreadyIsCopiedNotReadAgain) {
  const ScenarioAndRobot run = loadScenarioAndRobot(kScenarios + "/crack-descent.yaml", {});
  // The scenario's scene path under kBuild does not exist: only the description given can make
  // the wheels' scene. Another scene's description stands in for it.
  auto read = scene::loadSceneDescription(kScenarios + "/../scenes/step-crossing.xml");
  read.file = kBuild + "/scenes/pylon.xml";
  DriveOverrides given;
  given.scene_read = std::make_shared<const scene::SceneDescription>(read);
  const DriveSetup setup = configureDrive(run, given, kBuild);
  ASSERT_TRUE(setup.wheel_scene.valid());
  const auto wheel_scene = setup.wheel_scene.get();
  EXPECT_EQ(wheel_scene->scene_file, kBuild + "/scenes/pylon.xml");
  EXPECT_EQ(wheel_scene->pose_element, "robot_pose");
  EXPECT_NE(wheel_scene->world, nullptr);
  EXPECT_GT(wheel_scene->reach_m, 0.0);
  // A description of another file is not used: the drive reads its own, which is missing here.
  read.file = kBuild + "/scenes/other.xml";
  given.scene_read = std::make_shared<const scene::SceneDescription>(read);
  const DriveSetup own = configureDrive(run, given, kBuild);
  ASSERT_TRUE(own.wheel_scene.valid());
  EXPECT_ANY_THROW(own.wheel_scene.get());
}

TEST(DriveConfigure, WallWheelsOnChoosesWhatTheWheelsStandOn) {
  const std::string file = kScenarios + "/crack-descent.yaml";
  // The default: the scene's surface.
  EXPECT_NE(configureDrive(loadScenarioAndRobot(file, {}), {}, kBuild).params.ground, nullptr);
  // plane: the wall plane (no ground), for either backend.
  EXPECT_EQ(configureDrive(loadScenarioAndRobot(file, {"wall.wheels_on=plane"}), {}, kBuild).params.ground, nullptr);
  // surface: the scene's surface under the direct backend. The simbody backend has only the
  // plane: asking for both is one line naming the scenario file and the key.
  const ScenarioAndRobot surface = loadScenarioAndRobot(file, {"wall.wheels_on=surface"});
  EXPECT_NE(configureDrive(surface, {}, kBuild).params.ground, nullptr);
  DriveOverrides simbody;
  simbody.contact = "simbody";
  try {
    configureDrive(surface, simbody, kBuild);
    ADD_FAILURE() << "the simbody backend was given the surface";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("crack-descent.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("wall.wheels_on = surface"), std::string::npos) << e.what();
  }
  const ScenarioAndRobot plane = loadScenarioAndRobot(file, {"wall.wheels_on=plane"});
  EXPECT_EQ(configureDrive(plane, simbody, kBuild).params.ground, nullptr);
}

TEST(DriveConfigure, WithoutAScenarioTheModelsDefaults) {
  const ScenarioAndRobot run = loadScenarioAndRobot("", {});
  const DriveSetup setup = configureDrive(run, {}, kBuild);
  EXPECT_EQ(setup.start.x_m, 0.0);
  EXPECT_EQ(setup.start.yaw_rad, 0.0);
  EXPECT_EQ(setup.wall.gravity_y, WallOrientation::vertical().gravity_y);
  EXPECT_EQ(setup.params.substep_s, DriveParams{}.substep_s);
  EXPECT_EQ(setup.hold_until_ns, 0);
  EXPECT_FALSE(setup.end_on_fall);
  EXPECT_EQ(setup.scene_file, "");
}

TEST(DriveConfigure, EachOptionChangesTheValueItNames) {
  const ScenarioAndRobot run = loadScenarioAndRobot("", {});
  const DriveSetup base = configureDrive(run, {}, kBuild);
  auto with = [&](auto set) {
    DriveOverrides o;
    set(o);
    return differences(base, configureDrive(run, o, kBuild));
  };
  using Names = std::vector<std::string>;
  EXPECT_EQ(with([](DriveOverrides& o) { o.x_m = 0.5; }), Names{"start.x_m"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.y_m = 0.5; }), Names{"start.y_m"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.yaw_deg = 90.0; }), Names{"start.yaw_rad"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.wall = "floor"; }), Names{"wall"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.substep_hz = 2000.0; }), Names{"params.substep_s"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.contact = "simbody"; }), Names{"params.contact_backend"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.hold_s = 1.5; }), Names{"hold_until_ns"});
  EXPECT_EQ(with([](DriveOverrides& o) { o.downforce_n = 1000.0; }), Names{"downforce_n"});
  // Without the adhesion input the robot's desired downforce holds for the whole run.
  EXPECT_EQ(with([](DriveOverrides& o) { o.inputs = "command"; }), (Names{"downforce_n", "inputs"}));
  DriveOverrides command_only;
  command_only.inputs = "command";
  EXPECT_EQ(configureDrive(run, command_only, kBuild).downforce_n, run.robot.adhesion.desired_downforce_n);
}

TEST(DriveConfigure, BadOptionsAreNamed) {
  const ScenarioAndRobot run = loadScenarioAndRobot("", {});
  auto message = [&](auto set) -> std::string {
    DriveOverrides o;
    set(o);
    try {
      configureDrive(run, o, kBuild);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message([](DriveOverrides& o) { o.substep_hz = 50.0; }).find("--substep-hz"), std::string::npos);
  EXPECT_NE(message([](DriveOverrides& o) { o.hold_s = -1.0; }).find("--hold-s"), std::string::npos);
  EXPECT_NE(message([](DriveOverrides& o) { o.x_m = NAN; }).find("--x-m"), std::string::npos);
  EXPECT_NE(message([](DriveOverrides& o) { o.wall = "sideways"; }).find("--wall"), std::string::npos);
  EXPECT_NE(message([](DriveOverrides& o) { o.contact = "magic"; }).find("--contact"), std::string::npos);
  EXPECT_NE(message([](DriveOverrides& o) { o.inputs = "brakes"; }).find("--inputs"), std::string::npos);
}

}  // namespace
}  // namespace climbsim::drive
