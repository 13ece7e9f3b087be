/// climbsim-clockctl: pause, resume, single-step, stop a running clock or change its
/// real-time factor (publishes one ClockControl sample).

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/topic_names.hpp"
#include "climbsim/dds_context.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/main_guard.hpp"
#include "clockPubSubTypes.h"

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-clockctl: control a running climbsim clock"};
  DdsSettings dds;
  double timeout_s = 10.0;
  std::uint32_t steps = 1;
  double rtf = 0.0;
  dds.addOptions(app);
  app.add_option("--timeout-s", timeout_s, "give up if no clock is found within this long [s]");
  app.require_subcommand(1);
  auto* pause = app.add_subcommand("pause", "hold after the step in progress");
  auto* resume = app.add_subcommand("resume", "go on at the current real-time factor");
  auto* step = app.add_subcommand("step", "grant N more steps, then hold (only while paused)");
  step->add_option("N", steps, "number of steps (>= 1)")->check(CLI::PositiveNumber);
  auto* stop = app.add_subcommand("stop", "end the run after the step in progress");
  auto* rtf_cmd = app.add_subcommand("rtf", "set the real-time factor (0 = as fast as possible)");
  rtf_cmd->add_option("FACTOR", rtf, "real-time factor >= 0")->required()->check(CLI::NonNegativeNumber);
  return guardedMain(app, argc, argv, "clockctl", [&]() -> int {
    dds.resolve();
    ClockControl control;
    control.sender("climbsim-clockctl");
    control.steps(steps);
    control.realtime_factor(rtf);
    if (pause->parsed()) control.command(CLOCK_PAUSE);
    if (resume->parsed()) control.command(CLOCK_RESUME);
    if (step->parsed()) control.command(CLOCK_SINGLE_STEP);
    if (stop->parsed()) control.command(CLOCK_STOP);
    if (rtf_cmd->parsed()) control.command(CLOCK_SET_REALTIME_FACTOR);

    Notifier notifier;
    DdsContext context(dds, "climbsim-clockctl");  // the name clock.control lists
    Writer<ClockControlPubSubType> writer(context, topic::kClockControl, qos::kControl, notifier);
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(static_cast<std::int64_t>(timeout_s * 1000));
    while (writer.matchedReaders() == 0) {
      const auto seen = notifier.generation();
      if (!notifier.waitChanged(seen, deadline) && writer.matchedReaders() == 0) {
        spdlog::error("no clock on domain {} within {} s", dds.domain_id, timeout_s);
        return kExitFailed;
      }
    }
    writer.write(control);
    if (!writer.waitAcknowledged(std::chrono::milliseconds(static_cast<std::int64_t>(timeout_s * 1000)))) {
      spdlog::error("the clock did not acknowledge the command within {} s", timeout_s);
      return kExitFailed;
    }
    return kExitOk;
  });
}
