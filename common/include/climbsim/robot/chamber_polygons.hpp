#pragma once
/// @file
/// Plane geometry of chamber outlines (polygons in the sealing plane, robot frame R): areas and
/// centroids by the shoelace formula, containment, overlap, and the sealing segments of a set of
/// chambers that share whole edges: every boundary piece between a chamber and the outside is
/// an outer segment, every boundary between two chambers a wall segment
/// (docs/robot-files.md#chambers-and-strips).

#include <string>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim::robot {

using Point = RobotGeometry::Point;
using Polygon = std::vector<Point>;

/// Signed area (1/2) sum (x_k y_k+1 - x_k+1 y_k) [m^2]: > 0 for a counter-clockwise polygon.
double signedArea(const Polygon& polygon);
/// Centroid of the enclosed area, (1 / 6A) sum (p_k + p_k+1)(x_k y_k+1 - x_k+1 y_k).
Point centroid(const Polygon& polygon);
/// The polygon counter-clockwise (reversed if it is clockwise).
Polygon counterClockwise(Polygon polygon);
/// True if `p` lies strictly inside `polygon` (farther than `margin_m` from its boundary).
bool strictlyInside(const Polygon& polygon, Point p, double margin_m = 1e-9);
/// Distance from `p` to the polyline `line` (open; >= 2 points) [m].
double distanceToPolyline(const std::vector<Point>& line, Point p);
/// True if two edges of the polygon cross or touch other than at shared neighbours' corners.
bool selfIntersects(const Polygon& polygon);
/// True if the interiors of the two polygons overlap (edges cross, or a corner or the
/// centroid of one lies strictly inside the other). Sharing edges is no overlap.
bool overlap(const Polygon& a, const Polygon& b);

/// The outcome of sealingSegments: the segments, or the problems that keep the strips from
/// being one closed outer loop with walls between neighbours.
struct SegmentsOrProblems {
  std::vector<RobotGeometry::SealingSegment> segments;
  std::vector<std::string> problems;  ///< empty when the chambers' strips are sound
};

/// Sealing segments of chambers given by counter-clockwise outlines (VolumeId = index):
/// for each chamber in order its connected outer boundary pieces ("outer<i>", "outer<i>b", ...),
/// then for each pair i < j sharing edges the wall pieces ("wall<i>_<j>", ...), lengths as
/// the polylines' lengths. Problems: an edge that runs along a neighbour's edge without the
/// same corners, and an outer boundary that is not one closed loop (separate groups of
/// chambers, or a hole).
SegmentsOrProblems sealingSegments(const std::vector<Polygon>& outlines);

}  // namespace climbsim::robot
