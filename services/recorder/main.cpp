/// climbsim-recorder: a roster member (so the trace is complete) that writes trace.csv (one row
/// per step, docs/scenario-files.md), summary.json and run.mcap (every sample it reads, as it
/// travelled: docs/recordings.md) into --out. Its inputs come in record batches
/// (one delivery per producer per acknowledgement, not per topic per step: RecordedInput). Rows are
/// flushed within 20 ms (40 ms behind run.mcap's thread) and at the end: a run that ends early
/// keeps every row computed so far.
/// With --scenario the robot and the label come from the scenario file, and the run directory
/// keeps a copy of it as scenario.yaml; the sealing pictures of its pictures.sealing_at_s
/// (sealing/SealingPicture, published by climbsim-sealing) are written as
/// pictures/sealing_<kind>_<t>s.png. Pictures change nothing in trace.csv. With --depth-grids
/// it records scene/DepthGrid (the scene's reduced depth image every 0.1 s, in its record
/// batches) into viewer/depth_grids.jsonl: the wall of `climbsim view RUN_DIR`
/// (node/recorder_participant.hpp). With the scenario's recording.depth_images it also reads
/// every scene/DepthImage, as the sealing does, into run.mcap (docs/recordings.md#full-rate-depth-images).

#include "climbsim/logging.hpp"
#include "climbsim/service_command_line.hpp"
#include "configure.hpp"
#include "node/recorder_participant.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  ServiceCommandLine cli("climbsim-recorder: writes trace.csv and summary.json of a run",
                         "scenario file (deploy/scenarios/*.yaml): the robot and the default --label (its name) come "
                         "from it, and it is copied into --out as scenario.yaml; excludes --robot",
                         "duration_s=5");
  recorder::RecorderOverrides o;
  recorder::RunDirectory dir;
  CLI::App& app = cli.app;
  app.add_option("--out", dir.out_dir, "run directory to write trace.csv and summary.json into")->required();
  cli.addRobotOption("robot description (segment and wheel columns)");
  app.add_option("--inputs", o.inputs, "topics to record: chamber,adhesion,leakage,robot,drive or none");
  app.add_flag("--depth-grids", dir.depth_grids,
               "record scene/DepthGrid into viewer/depth_grids.jsonl (needs a scene writing depth on the roster)");
  bool no_mcap = false;
  app.add_flag("--no-mcap", no_mcap, "write no run.mcap (to measure what recording costs)");
  app.add_option("--label", o.label, "scenario name written into summary.json (default: the scenario's name)");
  return cli.run(argc, argv, "recorder", [&]() -> int {
    initLogging(cli.participant.name);
    const ScenarioAndRobot run = cli.load();
    recorder::RecorderSetup setup = recorder::configureRecorder(run, o);
    dir.scenario_file = cli.scenario_file;
    dir.overrides = cli.overrides;
    dir.robot_file = run.robot_file;
    dir.mcap = !no_mcap;
    return recorder::runRecorderParticipant(cli.participant, dir, setup);
  });
}
