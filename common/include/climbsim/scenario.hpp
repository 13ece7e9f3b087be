#pragma once
/// @file
/// A scenario (deploy/scenarios/*.yaml, docs/scenario-files.md): which robot on which scene, where
/// it starts, how long and how fast the lockstep runs, which controller, the drive-command
/// schedule, faults, the seed, and when the recorder takes pictures. SI units in every key.

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace climbsim {

struct Scenario {
  /// Start pose of the robot frame R on the wall, in the wall frame W (x horizontal, y up on a
  /// vertical wall).
  struct Start {
    double x_m = 0.0;
    double y_m = 0.0;
    double yaw_deg = 0.0;  ///< rotation of R about W's z; -90: R's x points down a vertical wall
    /// Until this time the robot is held at its start pose (the operator's hand or a safety
    /// rope while the vacuum builds up) [s], >= 0.
    double hold_s = 0.0;
  };
  enum class WallKind { kVertical, kFloor, kOverhang };
  /// What the drive's wheels stand on (docs/design.md#drive): the wall plane z_W = 0, or the
  /// scene's static surface under each wheel's tyre.
  enum class WheelsOn { kPlane, kSurface };
  /// Orientation of the wall plane; gravity follows from it.
  struct Wall {
    WallKind kind = WallKind::kVertical;
    /// Overhang only: how far the wall leans past vertical, (0, 90] degrees (90 = a ceiling).
    double overhang_deg = 0.0;
    /// wall.wheels_on: surface (the default) or plane.
    WheelsOn wheels_on = WheelsOn::kSurface;
  };
  /// Rates in Hz; depth_hz and laser_hz must divide the lockstep rate 1000 / step_ms.
  struct Rates {
    double drive_hz = 1000.0;  ///< the drive model's substep rate inside each step
    double depth_hz = 50.0;    ///< depth images (and sealing, which reads them)
    double laser_hz = 10.0;    ///< laser scans
  };
  /// The crack of the generated pylon (`climbsim-surface pylon`, block BLOCK_C1_R0: a
  /// horizontal rect crack across x 0..2 m at y = 0.70 m in W, the one crack-descent drives
  /// over). A scenario that sets it runs on a pylon generated for the run into
  /// RUN_DIR/scene/ (run_scene.hpp) instead of the build's $BUILD/scenes/pylon.xml, so it
  /// needs `scene: $BUILD/scenes/pylon.xml`. A key left out keeps the shipped pylon's value.
  struct Crack {
    static constexpr double kDefaultWidth_m = 0.010;  ///< the shipped pylon's opening [m]
    static constexpr double kDefaultDepth_m = 0.040;  ///< the shipped pylon's depth [m]
    static constexpr double kMaxWidth_m = 0.5;        ///< a quarter of the 2 m block [m]
    static constexpr double kMaxDepth_m = 1.0;        ///< half the 2 m block [m]
    double width_m = kDefaultWidth_m;  ///< opening, (0, 0.5] [m]
    double depth_m = kDefaultDepth_m;  ///< depth below the concrete's mean plane, (0, 1] [m]
  };
  /// The depth camera under the robot (scene and sealing read it).
  struct DepthCamera {
    /// The largest image side [px]: the DepthImage topic holds up to 2048 x 2048 heights
    /// (idl/scene.idl).
    static constexpr int kMaxSizePx = 2048;
    /// Image side [px], square, 1..kMaxSizePx; 0: the scene camera's (256 for the default scene).
    int size_px = 0;
    /// Sub-pixel leakage (docs/design.md#sub-pixel-leakage), the default: the scene averages
    /// rays over the depth pixels an edge of the wall crosses and gives them support heights, and
    /// the sealing weighs each pixel by the share of its square inside each strip. false: one ray
    /// per pixel centre, a pixel in the strip whose centre line is nearest its centre.
    bool subpixel = true;
  };
  /// none: valves closed; fixed: constant openings; reference: the adhesion controller;
  /// external: a client in another process commands; recorded: the commands of a recorded run
  /// played back open-loop (docs/recordings.md#replaying-commands).
  enum class ControllerKind { kNone, kFixed, kReference, kExternal, kRecorded };
  struct Controller {
    ControllerKind kind = ControllerKind::kReference;
    double downforce_n = 0.0;        ///< reference: set-point; 0 = the robot file's desired downforce
    bool balance = true;             ///< reference: keep P_F at the centre
    /// fixed: openings of the valves of chambers 1..N, in [0, 1]; N must be the robot's chamber
    /// count (checkScenarioAgainstRobot, scenario_and_robot.hpp).
    std::vector<double> valves;
    int valves_line = 0;             ///< line of controller.valves in the scenario file (0: none)
    /// recorded: the run.mcap whose ValveCommand and EngineCommand samples are played back,
    /// absolute (a relative path is taken against the scenario file's folder).
    std::string commands_file;
  };
  /// From t_s on the drive is commanded this body velocity (keys left out keep their value).
  struct DriveCommand {
    double t_s = 0.0;
    double vx_mps = 0.0;
    double vy_mps = 0.0;
    double wz_radps = 0.0;
  };
  enum class FaultKind { kValveStuck, kEngineFailure };
  struct Fault {
    double t_s = 0.0;
    FaultKind kind = FaultKind::kValveStuck;
    int chamber = 0;       ///< valve_stuck: chamber 1..7
    double opening = 0.0;  ///< valve_stuck: the opening it sticks at, [0, 1]
    int engine = 0;        ///< engine_failure: engine 1..N (it stops)
  };
  /// When the recorder writes pictures (simulation seconds).
  struct Pictures {
    std::vector<double> sealing_at_s;  ///< sealing pictures (edges and gaps)
    std::vector<double> ring_at_s;     ///< chamber ring pictures with wheel loads
  };
  /// What run.mcap holds besides what the recorder always records (docs/recordings.md).
  struct Recording {
    /// Every depth image the scene renders, whole, as scene/DepthImage samples and as
    /// foxglove.Grid on foxglove/depth_image (docs/recordings.md#full-rate-depth-images).
    bool depth_images = false;
    /// The controller's ValveCommand, EngineCommand and DriveCommand samples, as they travelled
    /// (docs/recordings.md#replaying-commands): what a recorded controller plays back.
    bool commands = false;
  };

  std::string source;  ///< the file it was read from
  std::string name;
  /// As written: a shipped robot's name (`cromsci`, deploy/robots/<name>.yaml), or a path,
  /// absolute or relative to the scenario file's directory.
  std::string robot_file;
  int robot_line = 0;      ///< line of `robot:` in the scenario file (0: unknown)
  /// The scene XML. "$BUILD/..." names a file generated at build time (build/scenes/pylon.xml).
  std::string scene_file;
  /// Set: the pylon's crack is changed (Crack); the scene is generated per run.
  std::optional<Crack> crack;
  Start start;
  Wall wall;
  double duration_s = 0.0;
  std::int64_t step_ns = 5'000'000;
  Rates rates;
  DepthCamera depth_camera;
  Controller controller;
  std::vector<DriveCommand> drive;  ///< in time order, the first at t_s = 0
  std::vector<Fault> faults;        ///< in time order
  Pictures pictures;
  Recording recording;
  /// What ends a run before its duration.
  struct EndOn {
    /// The robot left the wall (the drive's `fell`: centre more than 5 cm off the wall, no
    /// wheel contact for 0.1 s, or sliding faster than 1 m/s): the run ends with outcome
    /// "fell" and exit code 5. false: simulate the fall to the end of the run.
    bool fall = true;
    /// A sealing segment hangs over nothing (10 % of its strip sees no wall: past the edge of
    /// the scene, or over a hole deeper than the depth camera's far limit): true ends the run
    /// there as failed, with the segment and time as its reason; false (default): warn and go on.
    bool seal_over_nothing = false;
  };
  EndOn end_on;
  std::uint64_t seed = 1;
  /// A robot that slides farther than this along the wall over the run has lost its grip: the
  /// recorder's summary counts it as a failure of the adhesion controller (`slid`) [m], > 0.
  double slide_limit_m = 0.005;

  /// Keys of the file that an override made meaningless and that were left out, one line each
  /// ("<file>:<line>: controller.downforce_n = 2200 is ignored: ..."): `--set controller.type=none`
  /// on a file with a reference controller's set-point. The caller that talks to the user
  /// (launcher, solo) prints them as warnings; the run's resolved copy no longer has them.
  std::vector<std::string> ignored;

  /// Steps between two depth images (= lockstep period of scene and sealing).
  std::int64_t depthPeriodSteps() const;
  std::int64_t laserPeriodSteps() const;
  /// `robot_file` and `scene_file` resolved: relative paths against the scenario file's
  /// directory, "$BUILD/" against build_dir.
  std::string robotPath() const;
  std::string scenePath(const std::string& build_dir) const;
};

/// The command of `schedule` in force at clock time t_ns: the last entry whose t_s, rounded to
/// whole nanoseconds, is <= t_ns (integer comparison, so a step never misses its entry).
Scenario::DriveCommand driveCommandAt(const std::vector<Scenario::DriveCommand>& schedule, std::int64_t t_ns);

/// Reads and validates a scenario; `overrides` are "dotted.key=value" (the CLI's --set), applied
/// to the YAML before validation (value parsed as YAML, so lists work: `controller.valves=[...]`).
/// `--set controller.type=T` leaves out the file's controller keys that T does not take
/// (downforce_n but for reference, valves but for fixed, commands but for recorded), each noted
/// in Scenario::ignored;
/// such a key given by an override too is an error as in the file.
/// Every problem is a ConfigError with one line "<file>:<line>: <key> = <value>: <why>"; an
/// override that names no existing key path is reported as "--set <key>: ...".
Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides = {});

/// The same from text (tests); `source` names it in messages and anchors relative paths.
Scenario parseScenarioText(const std::string& yaml_text, const std::string& source,
                           const std::vector<std::string>& overrides = {});

/// The scene a scenario names as written for the generated pylon (Scenario::Crack needs it).
inline constexpr const char* kGeneratedPylonScene = "$BUILD/scenes/pylon.xml";

/// The scenario at `path` with `overrides` applied and its robot and scene paths made absolute
/// (scene against build_dir where it starts with $BUILD/), as YAML text: the copy a run
/// directory keeps and every service of the run reads. Validated like loadScenario.
/// `run_scene`: the scene generated for this run (a scenario with `crack`, run_scene.hpp); it
/// becomes `scene`, and `crack` is left out of the copy (a comment keeps its values), so the
/// copy names a scene that exists and runs again as it is. Required (ConfigError otherwise)
/// exactly when the scenario has a crack.
std::string resolvedScenarioText(const std::string& path, const std::vector<std::string>& overrides,
                                 const std::string& build_dir, const std::string& run_scene = "");

const char* toString(Scenario::ControllerKind kind);
const char* toString(Scenario::WallKind kind);

}  // namespace climbsim
