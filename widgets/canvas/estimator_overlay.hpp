#pragma once
// The localization overlay of the map canvas: estimator poses (dead reckoning, EKF, encoder +
// gyro) each with its 2-sigma position ellipse and a heading wedge of +/-2 sigma, the map
// features the last update matched (walls and corners/edges highlighted), the echo the sensor
// heard, and the initial pose being dragged out. Plain data plus one paint function; world
// metres and radians in, drawn through the canvas's MapView.

#include <Eigen/Core>
#include <QColor>
#include <QString>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "widgets/canvas/map_view.hpp"

class QPainter;

namespace irgs::widgets {

struct EstimatorPoseMarker {
  QString label;  // drawn beside the pose ("EKF", "DR")
  QColor colour;
  irgs::Pose2 pose;
  // Covariance of (x, y, theta), world frame; no ellipse or wedge when absent or not finite.
  std::optional<Eigen::Matrix3d> covariance;
};

struct MatchedFeatureMarker {
  std::optional<irgs::Segment> wall;       // the matched wall face's piece
  std::optional<irgs::Vec2> point;         // or the matched corner/edge
  irgs::Vec2 sensor = irgs::Vec2::Zero();  // where the reading was taken (true sensor position)
  bool accepted = true;                    // false: matched but gated out (drawn dashed)
};

struct EstimatorOverlay {
  std::vector<EstimatorPoseMarker> poses;
  std::vector<MatchedFeatureMarker> matches;  // of the newest update
  std::optional<irgs::Pose2> drag_pose;       // initial pose being set by dragging

  bool empty() const { return poses.empty() && matches.empty() && !drag_pose; }
};

// Semi-axes (metres) and orientation (radians, CCW from +x) of the k-sigma ellipse of a 2x2
// position covariance; nullopt when it is not finite or not positive semi-definite.
struct Ellipse2 {
  double major_m = 0.0;
  double minor_m = 0.0;
  double angle_rad = 0.0;
};
std::optional<Ellipse2> sigmaEllipse(const Eigen::Matrix2d& covariance, double k_sigma);

// Draws the overlay. Non-finite poses are skipped.
void paintEstimatorOverlay(QPainter& p, const MapView& view, const EstimatorOverlay& overlay);

}  // namespace irgs::widgets
