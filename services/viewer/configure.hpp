#pragma once
/// @file
/// climbsim-viewer's configuration (docs/design.md#configuration): its options with their
/// defaults, and the run description a scenario gives the page (the robot's shape, the
/// set-point). climbsim-viewer's main and its live and replay servers take them from here.

#include <string>

#include "web_server.hpp"

namespace climbsim::viewer {

struct ViewerOptions {
  std::string scenario_file;         ///< --scenario: the run's (live view)
  std::string replay_dir;            ///< --replay: serve this run directory instead of a live run
  std::string name = "viewer";       ///< DDS participant name (logs)
  WebServer::Options web;            ///< --port, --port-tries, --bind, --web-dir
  double max_fps = 30.0;             ///< states looked at per second (samples plotted)
  double messages_per_s = 10.0;      ///< messages per second to each page, each with its samples
  double depth_fps = 1.0;            ///< depth grids per second (the wall under the robot)
  int depth_cells = 128;             ///< a depth grid's side [cells]
  double linger_s = 2.0;             ///< after the run ended, keep serving this long [s]
  bool no_depth = false;             ///< no wall relief (no depth grids, no depth images)
  int nice = 10;                     ///< CPU priority of the live viewer (0 = as the run's services)
};

/// The page's hello message (run_description.hpp helloJson) for `mode` ("live" or "replay")
/// from `scenario_file`, as JSON text; "" for no file. loadScenario's ConfigErrors.
std::string helloText(const std::string& mode, const std::string& scenario_file);

}  // namespace climbsim::viewer
