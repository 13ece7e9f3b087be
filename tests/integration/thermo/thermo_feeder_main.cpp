/// climbsim-test-thermo-feeder: feeds climbsim-thermo in the integration tests. Each due
/// step it writes its share of sealing/Leakage (l_i * L_basic * --leak-scale of the robot)
/// and, with --commands, ValveCommand (every valve at --valve-opening) and EngineCommand
/// (every engine on at full speed). With --record it reads thermo/ChamberState and
/// thermo/AdhesionForce and writes them, one line per sample with every double in hexfloat,
/// so that two runs can be compared byte for byte.

#include <cstdio>
#include <fstream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "params_from_robot.hpp"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"
#include "thermo_translate.hpp"
#include "participant/exact_text.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

namespace {

using climbsim::records::hexText;

/// Segment indices of a --leakage spec: "all", "none", or "I/N" (index % N == I).
std::vector<std::size_t> leakageShare(const std::string& spec, std::size_t count) {
  std::vector<std::size_t> out;
  if (spec == "none") return out;
  std::size_t shard = 0, shards = 1;
  if (spec != "all") {
    const auto slash = spec.find('/');
    try {
      if (slash == std::string::npos) throw std::invalid_argument(spec);
      shard = std::stoul(spec.substr(0, slash));
      shards = std::stoul(spec.substr(slash + 1));
    } catch (const std::exception&) {
      throw climbsim::ConfigError("--leakage = '" + spec + "': expected all, none or I/N");
    }
    if (shards == 0 || shard >= shards) {
      throw climbsim::ConfigError("--leakage = '" + spec + "': expected I < N");
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (i % shards == shard) out.push_back(i);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-test-thermo-feeder: feeds and records climbsim-thermo in tests"};
  ParticipantOptions options;
  std::string robot_file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  std::string leakage_spec = "all";
  bool commands = false;
  double valve_opening = 1.0;
  double leak_scale = 1.0;
  std::string record_file;
  options.addOptions(app);
  app.add_option("--robot", robot_file, "robot description");
  app.add_option("--leakage", leakage_spec, "segments to publish: all, none, or I/N (index % N == I)");
  app.add_option("--leak-scale", leak_scale, "leak areas in units of the basic leakage l_i * L_basic (>= 0)");
  app.add_flag("--commands", commands, "publish ValveCommand and EngineCommand (engines on, full speed)");
  app.add_option("--valve-opening", valve_opening, "opening of every valve with --commands, 0..1");
  app.add_option("--record", record_file, "read ChamberState and AdhesionForce and write them to this file");
  return guardedMain(app, argc, argv, "test-thermo-feeder", [&]() -> int {
    initLogging(options.name);
    const RobotDescription robot = loadRobotDescription(robot_file);
    const RobotGeometry geometry = computeGeometry(robot);
    const auto names = thermo::segmentNames(geometry);
    if (!(leak_scale >= 0.0)) throw ConfigError("--leak-scale = " + std::to_string(leak_scale) + ": must be >= 0");
    auto areas = thermo::basicLeakAreas(robot, geometry);
    for (double& a : areas) a *= leak_scale;
    const auto share = leakageShare(leakage_spec, names.size());

    LockstepParticipant participant(options);
    auto* leakage = share.empty() ? nullptr : &participant.output<LeakagePubSubType>(thermo::topic::kLeakage);
    auto* valves = commands ? &participant.output<ValveCommandPubSubType>(thermo::topic::kValveCommand) : nullptr;
    auto* engines = commands ? &participant.output<EngineCommandPubSubType>(thermo::topic::kEngineCommand) : nullptr;
    StampedInput<ChamberStatePubSubType>* chamber_state = nullptr;
    StampedInput<AdhesionForcePubSubType>* adhesion = nullptr;
    std::ofstream record;
    if (!record_file.empty()) {
      record.open(record_file, std::ios::trunc);
      if (!record) throw ConfigError("--record = '" + record_file + "': cannot write it");
      chamber_state = &participant.input<ChamberStatePubSubType>(thermo::topic::kChamberState);
      adhesion = &participant.input<AdhesionForcePubSubType>(thermo::topic::kAdhesionForce);
    }

    auto leakage_sample = thermo::leakageToIdl(names, areas, std::vector<double>(names.size(), robot.sealing.basic_gap_m),
                                               share);
    // One valve per chamber with a reservoir, none without.
    const std::vector<double> opening(geometry.has_reservoir ? geometry.chambers.size() : 0, valve_opening);
    auto valve_sample = thermo::valveCommandToIdl(opening);
    auto engine_sample = thermo::engineCommandToIdl(std::vector<thermo::EngineCommand>(
        static_cast<std::size_t>(robot.engines.count), thermo::EngineCommand{true, 1.0}));

    const int code = participant.run([&](const StepContext& ctx) {
      if (record.is_open()) {
        for (const auto& s : chamber_state->get(ctx)) {
          record << ctx.step << " chamber " << s.source().c_str() << ' ' << s.step() << ' ' << s.t_ns();
          for (double v : s.pressure_pa()) record << ' ' << hexText(v);
          for (double v : s.valve_opening()) record << ' ' << hexText(v);
          for (double v : s.engine_speed()) record << ' ' << hexText(v);
          for (double v : s.segment_mass_flow_kgps()) record << ' ' << hexText(v);
          record << '\n';
        }
        for (const auto& s : adhesion->get(ctx)) {
          record << ctx.step << " force " << s.source().c_str() << ' ' << s.step() << ' ' << s.t_ns() << ' '
                 << hexText(s.downforce_n()) << ' ' << hexText(s.pf_x_m()) << ' ' << hexText(s.pf_y_m()) << '\n';
        }
      }
      if (leakage) leakage->write(ctx, leakage_sample);
      if (valves) valves->write(ctx, valve_sample);
      if (engines) engines->write(ctx, engine_sample);
    });
    record.flush();
    return code;
  });
}
