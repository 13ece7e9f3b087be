#pragma once
/// @file
/// All plots of a finished run directory (trace.csv, scenario.yaml): the library behind
/// climbsim-plot. Each plot is a function of the trace (and the scenario and robot) returning
/// an image; writeRunPlots writes them all.

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "line_chart.hpp"
#include "ring_picture.hpp"
#include "trace_table.hpp"

namespace climbsim::plot {

/// F over time with its set-point (dashed; the controller's published one, publishedSetpoint;
/// else `setpoint_n` labelled `setpoint_label`: the reference controller's downforce_n, else
/// the robot's desired downforce; a NaN `setpoint_n` draws none and puts the label into the
/// title, e.g. "controller: none, no set-point") and the downforce `hold_n` the wheels need not
/// to slip (m g / mu, dashed grey; none if <= 0), and P_F x and y [mm] over time in a panel
/// each (at least +-1 mm around a constant P_F).
cv::Mat downforcePlot(const TraceTable& trace, double setpoint_n, const std::string& setpoint_label,
                      double hold_n = 0.0, const std::vector<Marker>& marks = {});
/// p_1..p_N and, with a reservoir, p_R [kPa] over time, a panel each on one scale (small
/// multiples), with the ambient pressure dashed; `centre_chamber` (1..N, 0: none) is labelled
/// as a ring's centre.
cv::Mat pressuresPlot(const TraceTable& trace, int chamber_count, int centre_chamber, bool has_reservoir,
                      double ambient_pa, const std::vector<Marker>& marks = {});
/// valve1..valveN openings [0..1] over time, a panel each on one scale (robots with a reservoir).
cv::Mat valvesPlot(const TraceTable& trace, int valve_count, const std::vector<Marker>& marks = {});
/// wheel normal loads [N] (a panel per wheel, one scale) and slip speeds [m/s] (likewise).
cv::Mat wheelLoadsPlot(const TraceTable& trace, int wheel_count, const std::vector<Marker>& marks = {});

/// The moments every plot of a run marks: "released" at the scenario's start.hold_s (when > 0)
/// and "FELL" at summary.json's fell_at_s (when the run directory's summary has one).
std::vector<Marker> runMarkers(const Scenario& scenario, const std::string& run_dir);

/// The downforce [N] below which the wheels' friction cannot hold the robot's weight on the
/// scenario's wall: m g / mu on a vertical wall, m g (cos a / mu + sin a) on an overhang of a
/// past vertical, 0 on a floor.
double holdingDownforce(const Scenario& scenario, const RobotDescription& robot);

/// Scales for every ring picture of a run: pressures from the lowest chamber pressure of the
/// whole trace to max(ambient, highest), wheel circles by the largest load of the trace.
RingScales ringScales(const TraceTable& trace, int chamber_count, int wheel_count, double ambient_pa);
/// The values of row `row` for the ring picture.
RingMoment ringMoment(const TraceTable& trace, std::size_t row, int chamber_count, int wheel_count);

/// The set-point the controller published (trace column downforce_setpoint_n; NaN in rows that
/// stated none), dashed, labelled "set-point (the controller's)"; empty if no row has one.
/// downforce.png draws it in preference to downforceSetpoint: the set-point of whichever
/// controller ran, an external one too.
Series publishedSetpoint(const TraceTable& trace);

/// The set-point drawn in downforce.png when the trace has no published one, and its label:
/// the reference controller's (or the robot's desired F), the robot's desired F for an external
/// controller that published none, and none (NaN, the label says so) without a controller
/// or with fixed valves: they have no set-point.
struct Setpoint {
  double downforce_n = 0.0;
  std::string label;
};
Setpoint downforceSetpoint(const Scenario& scenario, const RobotDescription& robot);

/// Writes downforce.png, pressures.png, valves.png, wheel_loads.png and ring_<t>s.png for every
/// t of scenario.pictures.ring_at_s within the trace's time span into out_dir (created).
/// Reads run_dir/trace.csv and run_dir/scenario.yaml (and the robot file it names).
/// Returns the paths written; ConfigError on bad input (one line naming file, line/column,
/// value) or an unwritable out_dir.
std::vector<std::string> writeRunPlots(const std::string& run_dir, const std::string& out_dir);

}  // namespace climbsim::plot
