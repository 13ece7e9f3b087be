#pragma once
/// @file
/// The command line of climbsim-compose: one CLI11 app with a subcommand per command (up,
/// run, view, down, ps, logs, topics), each with only the options that command takes. main.cpp
/// parses with it; the help test compares deploy/climbsim's usage text with it.

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace climbsim::launcher {

/// Where the parsed command line lands.
struct CliValues {
  CommandContext context;    ///< --root, --build (as given; main makes them absolute)
  std::string compose_file;  ///< -f,--file of any command that takes it; empty: not given
  UpOptions up_options;      ///< options of `up` and `run`
  bool run_viewer = false;   ///< `run --viewer`
  ViewOptions view_options;  ///< options of `view`
  std::string run_name;      ///< RUN of `down`, `ps`, `logs`
  std::string service;       ///< SERVICE of `logs`
  bool down_all = false;     ///< `down --all`
};

/// climbsim-compose's command line, writing into `values` (which must outlive it). Every
/// command is a subcommand named as on the command line ("up", "run", ...).
std::unique_ptr<CLI::App> makeComposeCli(CliValues& values);

}  // namespace climbsim::launcher
