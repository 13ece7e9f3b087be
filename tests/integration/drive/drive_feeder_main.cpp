/// climbsim-test-drive-feeder: feeds climbsim-drive in the integration tests. Each due step
/// it writes a DriveCommand (--vx/--vy/--wz, body frame) and an AdhesionForce (--downforce at
/// --pf-x/--pf-y). With --record it reads drive/RobotState and drive/DriveState and writes
/// them, one line per sample with every double in hexfloat:
///   <step> robot <source> <stamp> <t_ns> <fell> <position x y z> <quaternion w x y z>
///   <step> wheels <source> <stamp> <t_ns> <fell> (<steering> <speed> <normal> <slip>) per wheel

#include <cstdio>
#include <fstream>

#include <CLI/CLI.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "drive_translate.hpp"
#include "robotPubSubTypes.h"
#include "thermoPubSubTypes.h"
#include "participant/exact_text.hpp"

using climbsim::records::hexText;

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-test-drive-feeder: feeds and records climbsim-drive in tests"};
  ParticipantOptions options;
  double downforce_n = 2200.0, pf_x_m = 0.0, pf_y_m = 0.0;
  drive::DriveCommand command;
  std::string record_file;
  options.addOptions(app);
  app.add_option("--downforce", downforce_n, "AdhesionForce.downforce_n [N]");
  app.add_option("--pf-x", pf_x_m, "AdhesionForce.pf_x_m [m]");
  app.add_option("--pf-y", pf_y_m, "AdhesionForce.pf_y_m [m]");
  app.add_option("--vx", command.vx_mps, "DriveCommand.vx_mps [m/s]");
  app.add_option("--vy", command.vy_mps, "DriveCommand.vy_mps [m/s]");
  app.add_option("--wz", command.wz_radps, "DriveCommand.wz_radps [rad/s]");
  app.add_option("--record", record_file, "read RobotState and DriveState and write them to this file");
  return guardedMain(app, argc, argv, "test-drive-feeder", [&]() -> int {
    initLogging(options.name);
    LockstepParticipant participant(options);
    auto& command_out = participant.output<DriveCommandPubSubType>(drive::topic::kDriveCommand);
    auto& adhesion_out = participant.output<AdhesionForcePubSubType>(drive::topic::kAdhesionForce);
    StampedInput<RobotStatePubSubType>* robot_state = nullptr;
    StampedInput<DriveStatePubSubType>* drive_state = nullptr;
    std::ofstream record;
    if (!record_file.empty()) {
      record.open(record_file, std::ios::trunc);
      if (!record) throw ConfigError("--record = '" + record_file + "': cannot write it");
      robot_state = &participant.input<RobotStatePubSubType>(drive::topic::kRobotState);
      drive_state = &participant.input<DriveStatePubSubType>(drive::topic::kDriveState);
    }
    auto command_sample = drive::driveCommandToIdl(command);
    auto adhesion_sample = drive::adhesionForceToIdl(downforce_n, pf_x_m, pf_y_m);

    const int code = participant.run([&](const StepContext& ctx) {
      if (record.is_open()) {
        for (const auto& s : robot_state->get(ctx)) {
          record << ctx.step << " robot " << s.source().c_str() << ' ' << s.step() << ' ' << s.t_ns() << ' '
                 << (s.fell() ? 1 : 0);
          for (double v : s.position_m()) record << ' ' << hexText(v);
          for (double v : s.orientation_wxyz()) record << ' ' << hexText(v);
          record << '\n';
        }
        for (const auto& s : drive_state->get(ctx)) {
          record << ctx.step << " wheels " << s.source().c_str() << ' ' << s.step() << ' ' << s.t_ns() << ' '
                 << (s.fell() ? 1 : 0);
          for (const auto& w : s.wheels()) {
            record << ' ' << hexText(w.steering_rad()) << ' ' << hexText(w.wheel_speed_radps()) << ' '
                   << hexText(w.normal_force_n()) << ' ' << hexText(w.slip_mps());
          }
          record << '\n';
        }
      }
      command_out.write(ctx, command_sample);
      adhesion_out.write(ctx, adhesion_sample);
    });
    record.flush();
    return code;
  });
}
