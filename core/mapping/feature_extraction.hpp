#pragma once
// Feature extraction for the hybrid map (003_… section 3.2, digest 4.4): plane (wall line)
// segments, concave corners and convex edges found in the weighted occupancy grid that the
// sonar cones build, in the form the paper-000 EKF matches against (walls as lines, corners and
// edges as points: core/estimation/localization_map.hpp, core/world/wall_model.hpp).
//
// Method (deterministic: no random sampling, ties broken by index):
//  1. Wall evidence: the centres of cells whose log-odds exceed occupied_log_odds and that have
//     known free space within free_support_distance_m, each weighted by its log-odds (a wall
//     seen by many cones counts more than a stray arc).
//  2. Lines by weighted Hough voting with peeling: the strongest (angle, offset) bin gives a
//     candidate line; the cells within inlier_distance_m of it are refitted by weighted total
//     least squares (twice, re-gathering the band each time), split where consecutive cells
//     along the line are more than max_gap_m apart, and every piece long and dense enough is
//     kept, refitted once more and its cells' votes withdrawn. A peak giving no piece is
//     suppressed. Repeats until no bin holds the weight of the shortest acceptable line.
//  3. Collinear pieces (angle < merge_angle_rad, each end within merge_offset_m of the other
//     line, gap <= max_gap_m, or <= bridge_gap_m behind a side that is not seen through) are
//     merged and refitted on their joint cells. Lines without known free space beside them and
//     "ghosts" (weaker parallel lines just in front of a stronger wall, traced by oblique cone
//     arcs) are dropped.
//  4. Junctions: two lines whose infinite lines cross within junction_reach_m of both segments
//     and form a wedge of 60-120 deg (corner_min/max_angle_rad). The wedge is probed
//     probe_distance_m from the crossing along its bisector: known free space there makes a
//     concave corner (the robot is inside the wedge, as in a room corner); occupied or unknown
//     inside and free space on the opposite side of two line ends make a convex edge (the
//     corner of an obstacle).
//  5. Free line ends: a line end that meets no other line and continues into known free space
//     (a door jamb, a free-standing wall) is a convex edge.
//
// Units: metres and radians, world frame of the grid.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct FeatureExtractionParams {
  // Cells above are wall evidence (p > 0.88): stray arcs that other cones partly cleared stay
  // below, walls seen by many cones saturate near the clamp.
  double occupied_log_odds = 2.0;
  double free_log_odds = -0.5;  // probed cells below are known free (p < 0.38)
  // Evidence cells with no known free cell within this distance are ignored: a sonar arc that
  // crosses a wall behind it (an echo from a farther surface) is never cleared there.
  double free_support_distance_m = 0.05;
  double hough_angle_step_rad = degToRad(1.0);
  double hough_rho_step_m = 0.02;
  double inlier_distance_m = 0.03;  // half width of the band of cells gathered around a line
  double max_gap_m = 0.12;          // a line splits where its cells are farther apart
  double min_line_length_m = 0.3;
  // Fraction of a line's length covered by cells (projected at the grid resolution): rejects
  // sparse lines through scattered cells.
  double min_fill = 0.6;
  double merge_angle_rad = degToRad(3.0);
  double merge_offset_m = 0.03;
  // Collinear pieces up to this far apart are joined when one side of the gap is not known free
  // (an outer wall whose face was cleared by grazing cones); a gap seen through on both sides
  // is an opening and stays one.
  double bridge_gap_m = 0.6;
  // A line must have known free space beside it along at least this share of its length on
  // one side: a surface nobody has seen from free space is not a wall face.
  double min_free_side = 0.5;
  // A weaker line parallel to a stronger one, within this distance on the stronger one's free
  // side, is the trace of oblique sonar arcs in front of that wall and is dropped.
  double ghost_distance_m = 0.12;
  double corner_min_angle_rad = degToRad(60.0);  // wedge angle between the two lines' arms
  double corner_max_angle_rad = degToRad(120.0);
  // A junction's crossing lies within this of both segments (sonar walls often stop short of a
  // room corner, where the cones see the corner itself).
  double junction_reach_m = 0.5;
  double probe_distance_m = 0.08;        // how far from a junction or line end free space is probed
  double point_merge_distance_m = 0.08;  // points of one kind closer than this are merged
  int max_lines = 2000;
};

// What is wrong with the parameters (non-finite, non-positive steps/lengths, free >= occupied
// log-odds, angles outside (0, pi), min > max, fill outside (0, 1]), or nothing.
std::optional<std::string> featureExtractionParamsError(const FeatureExtractionParams& params);

struct ExtractedLine {
  Segment segment;             // end points: the extreme projections of the supporting cells
  Vec2 normal = Vec2::Zero();  // unit normal on the left of segment.a -> segment.b
  double offset_m = 0.0;       // normal . p = offset_m for every point p of the line
  double weight = 0.0;         // summed log-odds of the supporting cells
  int cells = 0;               // supporting cells
  double rms_m = 0.0;          // weighted rms distance of the supporting cells to the line
  // Fraction of the probes at probe_distance_m beside the line that are known free, per side
  // (left / right of a -> b): which face(s) the robot has seen.
  double free_left = 0.0;
  double free_right = 0.0;
};

struct ExtractedPoint {
  PointFeatureKind kind = PointFeatureKind::kCorner;
  Vec2 position = Vec2::Zero();
  int line_a = -1;  // indices into FeatureExtractionResult::lines; line_b = -1 for a free end
  int line_b = -1;
  double wedge_angle_rad = 0.0;  // interior angle of the wedge (0 for a free line end)
};

struct FeatureExtractionResult {
  std::vector<ExtractedLine> lines;
  std::vector<ExtractedPoint> points;
  std::size_t evidence_cells = 0;  // cells above occupied_log_odds
  std::size_t assigned_cells = 0;  // of those, supporting an extracted line
  bool truncated = false;          // max_lines (or the peel iteration cap) was reached
};

// Extracts lines, corners and edges from the grid. Throws std::invalid_argument for parameters
// that featureExtractionParamsError rejects. An empty grid gives an empty result.
FeatureExtractionResult extractFeatures(const OccupancyGrid& grid,
                                        const FeatureExtractionParams& params = {});

}  // namespace irgs
