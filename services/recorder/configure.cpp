#include "configure.hpp"

#include <cmath>

#include "climbsim/names.hpp"

namespace climbsim::recorder {
namespace {
RecordedInputs parseInputs(const std::string& list) {
  const auto chosen =
      parseChoiceList("--inputs", list, {"chamber", "adhesion", "leakage", "robot", "drive", "commands"});
  return RecordedInputs{chosen.count("chamber") != 0, chosen.count("adhesion") != 0, chosen.count("leakage") != 0,
                        chosen.count("robot") != 0,   chosen.count("drive") != 0,    chosen.count("commands") != 0};
}
}  // namespace

RecorderSetup configureRecorder(const ScenarioAndRobot& run, const RecorderOverrides& overrides) {
  RecorderSetup setup{TraceRecorder(segmentNames(run.geometry), basicLeakAreas(run.robot, run.geometry),
                                    static_cast<int>(run.geometry.wheels.size()), run.geometry.chamberCount(),
                                    run.geometry.has_reservoir),
                      overrides.label.value_or(""), parseInputs(overrides.inputs), {}, 0};
  if (const auto& scenario = run.scenario) {
    setup.trace.setSlideLimit(scenario->slide_limit_m);
    setup.trace.setEndOnFall(scenario->end_on.fall);
    setup.trace.setDownforceFrom(std::llround(scenario->start.hold_s * 1e9));
    if (!overrides.label) setup.label = scenario->name;
    setup.picture_times = scenario->pictures.sealing_at_s;
    setup.depth_period_ns = scenario->depthPeriodSteps() * scenario->step_ns;
    setup.inputs.depth_images = scenario->recording.depth_images;
    setup.inputs.commands = setup.inputs.commands || scenario->recording.commands;
  }
  setup.geometry = run.geometry;
  return setup;
}

}  // namespace climbsim::recorder
