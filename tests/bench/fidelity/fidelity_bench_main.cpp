/// climbsim-bench-fidelity: does the simulated physics depend on the depth camera's pixels?
/// (docs/benchmarks.md#fidelity). Solo runs (climbsim-solo, one core, no DDS) of
///
/// - crack-descent at its default resolution, 8..12 s, with sub-pixel leakage off
///   (`--set depth_camera.subpixel=false`) and on (the default,
///   docs/design.md#sub-pixel-leakage): the largest frame-to-frame change of the leak area of
///   any strip over the crack all the while, over that strip's mean (`leak_jump_max`), the
///   same less the strip's trend (`leak_jump_about_trend_max`), and the rms of the downforce
///   about its 0.2 s moving mean (`downforce_ripple_n`);
/// - crack-descent (8..12 s) and crack-upper-strips (6..12 s) with sub-pixel leakage at each of
///   --sizes px (`--set depth_camera.size_px=N`, up to 2048), each run ending 0.1 s after its
///   window (`--set duration_s=12.1`): the mean leak area of the strips over the crack and the mean
///   downforce, each against the finest size's; and crack-descent's ripple at the finest size
///   beside the ripple of the default run's downforce less the finest run's (the part of the
///   ripple that comes from the pixels);
/// - the same studies with the controller's decisions held: the finest run records its commands
///   (`--set recording.commands=true`) and each coarser size plays them back
///   (`--set controller.type=recorded`, docs/recordings.md#replaying-commands), so that the
///   coarse run's valves move exactly as the finest run's and what differs is the physics of the
///   pixels alone, not a controller's threshold crossed at another step.
///
///   bench: fidelity: scenario=crack-descent px=256 subpixel=false|true leak_jump_max=.. (SEGMENT ..) target=0.05 met=yes|no leak_jump_about_trend_max=.. target=0.05 met=yes|no downforce_ripple_n=.. target=15 met=yes|no step_us=..
///   bench: fidelity: convergence scenario=.. px=.. subpixel=true crack_leak_mm2=.. mean_downforce_n=.. leak_vs_finest=.. downforce_vs_finest=.. step_us=..
///   bench: fidelity: ripple scenario=crack-descent .. default px=.. downforce_ripple_n=.. reference: finest px=.. downforce_ripple_n=..; .. difference_ripple_n=..
///   bench: fidelity: held_commands scenario=.. px=.. crack_leak_mm2=.. mean_downforce_n=.. leak_vs_finest=.. downforce_vs_finest=..
///   bench: fidelity: ripple_held_commands scenario=crack-descent .. default px=.. downforce_ripple_n=.. difference_ripple_n=..
///   bench: fidelity: default px=.. leak_dev_max=.. downforce_dev_max=.. target=0.02 met=yes|no
///   bench: fidelity: default_held_commands px=.. leak_dev_max=.. downforce_dev_max=.. target=0.02 met=yes|no
///
/// and writes the same as JSON to --out.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/main_guard.hpp"
#include "fidelity/trace_fidelity.hpp"
#include "solo/solo_rtf.hpp"

namespace {

using climbsim::bench::LeakJump;
using climbsim::bench::Trace;

constexpr double kJumpTarget = 0.05;       // of the strip's mean
constexpr double kRippleTarget_n = 15.0;   // rms about the 0.2 s moving mean
constexpr double kConvergenceTarget = 0.02;  // of the finest size's value
constexpr double kRippleWindow_s = 0.2;

/// Where each scenario's crack lies under the robot for the whole window [s].
struct Study {
  std::string scenario;
  double t0_s;
  double t1_s;
};

struct Run {
  Study study;
  int px = 0;  ///< 0: the scenario's own resolution
  Trace trace;
  climbsim::bench::SoloCost cost;
  std::string dir;  ///< its run directory
};

/// `study`'s scenario at `px` (0: its own resolution), with sub-pixel leakage when `subpixel`;
/// `to_window_end`: the run ends 0.1 s after the study's window (the steps before are the same).
/// `commands`: "record" records the run's commands into its run.mcap; a run.mcap plays that
/// recording's commands back (a recorded controller); "": the scenario's controller.
Run runSolo(const std::string& build, const Study& study, int px, bool subpixel, bool to_window_end = false,
            const std::string& commands = "") {
  std::vector<std::string> overrides;
  if (commands == "record") {
    overrides.push_back("recording.commands=true");
  } else if (!commands.empty()) {
    overrides.push_back("controller.type=recorded");
    overrides.push_back("controller.commands=" + commands);
  }
  if (px > 0) overrides.push_back("depth_camera.size_px=" + std::to_string(px));
  if (to_window_end) {
    std::ostringstream end;
    end << "duration_s=" << study.t1_s + 0.1;
    overrides.push_back(end.str());
  }
  overrides.push_back(subpixel ? "depth_camera.subpixel=true" : "depth_camera.subpixel=false");
  const std::string label = "fidelity-" + study.scenario + (px > 0 ? "-" + std::to_string(px) : "") +
                            (subpixel ? "-subpixel" : "") + (commands.empty() || commands == "record" ? "" : "-held");
  Run run{study, px, {}, climbsim::bench::runSoloPinned(build, study.scenario, label, overrides), {}};
  run.dir = build + "/bench/" + label;
  run.trace = climbsim::bench::readTrace(run.dir + "/trace.csv");
  return run;
}

double stepUs(const Run& run) { return run.cost.steps > 0 ? 1e6 * run.cost.wall_s / run.cost.steps : 0.0; }

std::vector<int> parseSizes(const std::string& text) {
  std::vector<int> sizes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) sizes.push_back(std::stoi(item));
  std::sort(sizes.begin(), sizes.end());
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-fidelity: leakage continuity, downforce ripple and convergence in resolution"};
  std::string out_file;
  std::string build = CLIMBSIM_BUILD_DIR;
  std::string sizes_text = "256,512,1024,2048";
  int default_px = 256;
  bool no_convergence = false;
  app.add_option("--out", out_file, "JSON file to write");
  app.add_option("--build", build, "the build directory");
  app.add_option("--sizes", sizes_text, "depth image sides of the convergence study [px], comma-separated");
  app.add_option("--default-px", default_px, "the scenarios' default depth image side [px]");
  app.add_flag("--no-convergence", no_convergence, "only the continuity figures of crack-descent");
  return climbsim::guardedMain(app, argc, argv, "bench-fidelity", [&] {
    nlohmann::json doc;
    const Study descent{"crack-descent", 8.0, 12.0};
    const Study upper{"crack-upper-strips", 6.0, 12.0};

    // Continuity at the default resolution, sub-pixel leakage off and on.
    std::vector<Run> bases;
    for (const bool subpixel : {false, true}) {
      bases.push_back(runSolo(build, descent, 0, subpixel));
      const Run& base = bases.back();
      const auto jumps = climbsim::bench::leakJumps(base.trace, descent.t0_s, descent.t1_s, kRippleWindow_s);
      LeakJump worst, worst_about_trend;
      for (const LeakJump& j : jumps) {
        if (j.relative() >= worst.relative()) worst = j;
        if (j.relativeAboutTrend() >= worst_about_trend.relativeAboutTrend()) worst_about_trend = j;
      }
      const double ripple = climbsim::bench::downforceRipple_n(base.trace, descent.t0_s, descent.t1_s, kRippleWindow_s);
      const bool jump_met = !jumps.empty() && worst.relative() <= kJumpTarget;
      const bool about_trend_met = !jumps.empty() && worst_about_trend.relativeAboutTrend() <= kJumpTarget;
      const bool ripple_met = ripple <= kRippleTarget_n;
      std::printf("bench: fidelity: scenario=crack-descent px=%d subpixel=%s t=%g..%g s strips_over_crack=%zu "
                  "leak_jump_max=%.4f (%s at %.3f s: %.1f mm2 of mean %.1f mm2) target=%.2f met=%s "
                  "leak_jump_about_trend_max=%.4f (%s at %.3f s: %.1f mm2 off the 0.2 s mean change) target=%.2f "
                  "met=%s downforce_ripple_n=%.2f (rms about the %.1f s moving mean) target=%.0f met=%s step_us=%.1f\n",
                  default_px, subpixel ? "true" : "false", descent.t0_s, descent.t1_s, jumps.size(), worst.relative(),
                  worst.segment.c_str(), worst.jump_t_s, worst.jump_max_m2 * 1e6, worst.mean_m2 * 1e6, kJumpTarget,
                  jump_met ? "yes" : "no", worst_about_trend.relativeAboutTrend(), worst_about_trend.segment.c_str(),
                  worst_about_trend.about_trend_t_s, worst_about_trend.about_trend_max_m2 * 1e6, kJumpTarget,
                  about_trend_met ? "yes" : "no", ripple, kRippleWindow_s, kRippleTarget_n, ripple_met ? "yes" : "no",
                  stepUs(base));
      nlohmann::json mode;
      mode["subpixel"] = subpixel;
      mode["leak_jump_max"] = worst.relative();
      mode["leak_jump_segment"] = worst.segment;
      mode["leak_jump_mm2"] = worst.jump_max_m2 * 1e6;
      mode["leak_jump_t_s"] = worst.jump_t_s;
      mode["leak_mean_mm2"] = worst.mean_m2 * 1e6;
      mode["leak_jump_about_trend_max"] = worst_about_trend.relativeAboutTrend();
      mode["leak_jump_about_trend_segment"] = worst_about_trend.segment;
      mode["leak_jump_about_trend_t_s"] = worst_about_trend.about_trend_t_s;
      mode["downforce_ripple_n"] = ripple;
      mode["step_us"] = stepUs(base);
      mode["met"] = {{"leak_jump_max", jump_met},
                     {"leak_jump_about_trend_max", about_trend_met},
                     {"downforce_ripple_n", ripple_met}};
      for (const LeakJump& j : jumps) {
        mode["strips"].push_back({{"segment", j.segment},
                                  {"jump_mm2", j.jump_max_m2 * 1e6},
                                  {"mean_mm2", j.mean_m2 * 1e6},
                                  {"relative", j.relative()},
                                  {"about_trend", j.relativeAboutTrend()}});
      }
      doc["continuity"].push_back(mode);
    }
    doc["scenario"] = descent.scenario;
    doc["px"] = default_px;
    doc["window_s"] = {descent.t0_s, descent.t1_s};
    doc["targets"] = {{"leak_jump_max", kJumpTarget}, {"downforce_ripple_n", kRippleTarget_n},
                      {"convergence", kConvergenceTarget}};
    const Run& base = bases.back();

    if (!no_convergence) {
      const std::vector<int> sizes = parseSizes(sizes_text);
      double leak_dev_max = 0.0, force_dev_max = 0.0;
      double held_leak_dev_max = 0.0, held_force_dev_max = 0.0;  // with the finest run's commands
      for (const Study* study_of : {&descent, &upper}) {
        const Study& study = *study_of;
        std::vector<Run> runs;
        for (const int px : sizes) {
          // The default resolution's run of crack-descent is the continuity run above.
          if (&study == &descent && px == default_px) {
            runs.push_back(base);
            runs.back().px = px;
          } else {
            // The finest run records its commands for the held runs below (its trace is the same).
            runs.push_back(runSolo(build, study, px, true, true, px == sizes.back() ? "record" : ""));
          }
        }
        // With sub-pixel leakage (the default run of crack-descent is the continuity run with it).
        // The strips over the crack at the finest size, compared at every size.
        std::vector<std::string> strips;
        for (const LeakJump& j : climbsim::bench::leakJumps(runs.back().trace, study.t0_s, study.t1_s, kRippleWindow_s)) {
          strips.push_back("leak_area_m2_" + j.segment);
        }
        const double finest_leak = climbsim::bench::windowMean(runs.back().trace, strips, study.t0_s, study.t1_s);
        const double finest_force =
            climbsim::bench::windowMean(runs.back().trace, {"downforce_n"}, study.t0_s, study.t1_s);
        for (const Run& run : runs) {
          const double leak = climbsim::bench::windowMean(run.trace, strips, study.t0_s, study.t1_s);
          const double force = climbsim::bench::windowMean(run.trace, {"downforce_n"}, study.t0_s, study.t1_s);
          const double leak_dev = finest_leak > 0.0 ? leak / finest_leak - 1.0 : 0.0;
          const double force_dev = finest_force != 0.0 ? force / finest_force - 1.0 : 0.0;
          const auto run_jumps = climbsim::bench::leakJumps(run.trace, study.t0_s, study.t1_s, kRippleWindow_s);
          double jump = 0.0, about_trend = 0.0;
          for (const LeakJump& j : run_jumps) {
            jump = std::max(jump, j.relative());
            about_trend = std::max(about_trend, j.relativeAboutTrend());
          }
          const double run_ripple =
              climbsim::bench::downforceRipple_n(run.trace, study.t0_s, study.t1_s, kRippleWindow_s);
          std::printf("bench: fidelity: convergence scenario=%s px=%d subpixel=true t=%g..%g s crack_leak_mm2=%.2f "
                      "mean_downforce_n=%.1f leak_vs_finest=%+.4f downforce_vs_finest=%+.4f leak_jump_max=%.4f "
                      "leak_jump_about_trend_max=%.4f downforce_ripple_n=%.2f step_us=%.1f\n",
                      study.scenario.c_str(), run.px, study.t0_s, study.t1_s, leak * 1e6, force, leak_dev, force_dev,
                      jump, about_trend, run_ripple, stepUs(run));
          doc["convergence"].push_back({{"scenario", study.scenario},
                                        {"px", run.px},
                                        {"strips", strips.size()},
                                        {"crack_leak_mm2", leak * 1e6},
                                        {"mean_downforce_n", force},
                                        {"leak_vs_finest", leak_dev},
                                        {"downforce_vs_finest", force_dev},
                                        {"leak_jump_max", jump},
                                        {"leak_jump_about_trend_max", about_trend},
                                        {"downforce_ripple_n", run_ripple},
                                        {"step_us", stepUs(run)}});
          if (run.px == default_px) {
            leak_dev_max = std::max(leak_dev_max, std::abs(leak_dev));
            force_dev_max = std::max(force_dev_max, std::abs(force_dev));
          }
        }
        // The coarser sizes again, with the finest run's commands played back.
        const std::string finest_commands = runs.back().dir + "/run.mcap";
        nlohmann::json held_ripple = nlohmann::json::object();
        for (std::size_t i = 0; i + 1 < runs.size(); ++i) {
          const Run held = runSolo(build, study, runs[i].px, true, true, finest_commands);
          const double leak = climbsim::bench::windowMean(held.trace, strips, study.t0_s, study.t1_s);
          const double force = climbsim::bench::windowMean(held.trace, {"downforce_n"}, study.t0_s, study.t1_s);
          const double leak_dev = finest_leak > 0.0 ? leak / finest_leak - 1.0 : 0.0;
          const double force_dev = finest_force != 0.0 ? force / finest_force - 1.0 : 0.0;
          std::printf("bench: fidelity: held_commands scenario=%s px=%d t=%g..%g s crack_leak_mm2=%.2f "
                      "mean_downforce_n=%.1f leak_vs_finest=%+.4f downforce_vs_finest=%+.4f (reference: the %d px "
                      "run, whose commands this run plays back)\n",
                      study.scenario.c_str(), held.px, study.t0_s, study.t1_s, leak * 1e6, force, leak_dev, force_dev,
                      sizes.back());
          doc["held_commands"].push_back({{"scenario", study.scenario},
                                          {"px", held.px},
                                          {"crack_leak_mm2", leak * 1e6},
                                          {"mean_downforce_n", force},
                                          {"leak_vs_finest", leak_dev},
                                          {"downforce_vs_finest", force_dev}});
          if (held.px == default_px && &study == &descent) {
            // The ripple the pixels add with the decisions held: the held run's downforce less
            // the finest run's, and the held run's own.
            held_ripple = {{"downforce_ripple_n", climbsim::bench::downforceRipple_n(held.trace, study.t0_s, study.t1_s,
                                                                                   kRippleWindow_s)},
                           {"difference_ripple_n",
                            climbsim::bench::downforceDifferenceRipple_n(held.trace, runs.back().trace, study.t0_s,
                                                                          study.t1_s, kRippleWindow_s)}};
          }
          if (held.px == default_px) {
            held_leak_dev_max = std::max(held_leak_dev_max, std::abs(leak_dev));
            held_force_dev_max = std::max(held_force_dev_max, std::abs(force_dev));
          }
        }
        if (&study == &descent) {
          // How much of the default run's ripple is the pixels': its downforce less the finest
          // run's, beside the finest run's own ripple (what the physics and the controller give).
          const double finest_ripple =
              climbsim::bench::downforceRipple_n(runs.back().trace, study.t0_s, study.t1_s, kRippleWindow_s);
          const double difference_ripple = climbsim::bench::downforceDifferenceRipple_n(
              base.trace, runs.back().trace, study.t0_s, study.t1_s, kRippleWindow_s);
          std::printf("bench: fidelity: ripple scenario=%s t=%g..%g s default px=%d downforce_ripple_n=%.2f reference: "
                      "finest px=%d downforce_ripple_n=%.2f; the default's downforce less the finest's: "
                      "difference_ripple_n=%.2f\n",
                      study.scenario.c_str(), study.t0_s, study.t1_s, default_px,
                      climbsim::bench::downforceRipple_n(base.trace, study.t0_s, study.t1_s, kRippleWindow_s),
                      sizes.back(), finest_ripple, difference_ripple);
          doc["ripple"] = {{"finest_px", sizes.back()},
                           {"finest_downforce_ripple_n", finest_ripple},
                           {"difference_ripple_n", difference_ripple},
                           {"held_commands", held_ripple}};
          std::printf("bench: fidelity: ripple_held_commands scenario=%s t=%g..%g s default px=%d with the finest run's "
                      "commands: downforce_ripple_n=%.2f difference_ripple_n=%.2f (reference: finest px=%d "
                      "downforce_ripple_n=%.2f)\n",
                      study.scenario.c_str(), study.t0_s, study.t1_s, default_px,
                      held_ripple.value("downforce_ripple_n", 0.0), held_ripple.value("difference_ripple_n", 0.0),
                      sizes.back(), finest_ripple);
        }
      }
      const bool met = leak_dev_max <= kConvergenceTarget && force_dev_max <= kConvergenceTarget;
      std::printf("bench: fidelity: default px=%d vs finest px=%d leak_dev_max=%.4f downforce_dev_max=%.4f "
                  "target=%.2f met=%s\n",
                  default_px, sizes.back(), leak_dev_max, force_dev_max, kConvergenceTarget, met ? "yes" : "no");
      const bool held_met = held_leak_dev_max <= kConvergenceTarget && held_force_dev_max <= kConvergenceTarget;
      std::printf("bench: fidelity: default_held_commands px=%d vs finest px=%d (its commands played back) "
                  "leak_dev_max=%.4f downforce_dev_max=%.4f target=%.2f met=%s\n",
                  default_px, sizes.back(), held_leak_dev_max, held_force_dev_max, kConvergenceTarget,
                  held_met ? "yes" : "no");
      doc["default_held_leak_dev_max"] = held_leak_dev_max;
      doc["default_held_downforce_dev_max"] = held_force_dev_max;
      doc["met"]["convergence_held_commands"] = held_met;
      doc["finest_px"] = sizes.back();
      doc["default_leak_dev_max"] = leak_dev_max;
      doc["default_downforce_dev_max"] = force_dev_max;
      doc["met"]["convergence"] = met;
    }
    double load[1] = {0.0};
    if (getloadavg(load, 1) == 1) doc["loadavg"] = load[0];  // of this shared machine, at the end
    if (!out_file.empty()) std::ofstream(out_file) << doc.dump(2) << "\n";
    return 0;
  });
}
