/// climbsim-robot: robot files on their own (docs/robot-files.md).
///   show FILE --out PNG   draw the robot: outlines, chamber and strip numbers, wheels with their
///                         kinds, the reservoir/engine connections. Every problem of the file is
///                         listed (file:line: key = value: why), exit code 2.

#include <string>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/robot/robot_picture.hpp"
#include "climbsim/robot_names.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app("climbsim-robot: robot files (docs/robot-files.md)");
  app.require_subcommand(1);
  std::string file;
  std::string out;
  int width_px = 1200;
  CLI::App* show = app.add_subcommand("show", "draw a robot file: chambers, strips, wheels, reservoir and engines");
  show->add_option("FILE", file, "robot file, or a shipped robot's name (cromsci, single-chamber, grid-2x2, ring-12)")->required();
  show->add_option("--out", out, "PNG file to write")->required();
  show->add_option("--width", width_px, "picture width [px]")->check(CLI::Range(600, 4000));
  return guardedMain(app, argc, argv, "robot", [&]() -> int {
    file = robotFileOf(file);
    const RobotDescription description = loadRobotDescription(file);
    const RobotGeometry geometry = computeGeometry(description);
    const cv::Mat picture = robot::drawRobot(description, geometry, width_px);
    if (!cv::imwrite(out, picture, {cv::IMWRITE_PNG_COMPRESSION, 9})) throw ConfigError("--out " + out + ": cannot write the picture");
    spdlog::info("{}: {} chambers, {} sealing segments, {} wheels -> {}", file, geometry.chamberCount(),
                 geometry.segments.size(), geometry.wheels.size(), out);
    return kExitOk;
  });
}
