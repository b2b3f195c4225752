#include "widgets/canvas/estimator_overlay.hpp"

#include <Eigen/Eigenvalues>
#include <QFont>
#include <QPainter>
#include <QPainterPath>
#include <QPen>
#include <algorithm>
#include <cmath>

namespace irgs::widgets {
namespace {

constexpr double kWedgeRadius_px = 34.0;  // heading wedge length on screen
constexpr double kDotRadius_px = 3.5;
constexpr double kMaxWedgeHalf_rad = kPi;  // a wedge of +/-2 sigma, at most a full circle

bool finitePose(const irgs::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

// Qt's angles are degrees, counter-clockwise on screen; world theta is CCW with +y up, and the
// view flips y, so the on-screen angle equals the world angle.
void paintWedge(QPainter& p, const QPointF& centre, double theta, double half_width,
                const QColor& colour) {
  const double half = std::min(half_width, kMaxWedgeHalf_rad);
  QPainterPath wedge;
  wedge.moveTo(centre);
  const QRectF box(centre.x() - kWedgeRadius_px, centre.y() - kWedgeRadius_px, 2 * kWedgeRadius_px,
                   2 * kWedgeRadius_px);
  wedge.arcTo(box, radToDeg(theta - half), radToDeg(2 * half));
  wedge.closeSubpath();
  QColor fill = colour;
  fill.setAlpha(55);
  p.setBrush(fill);
  p.setPen(Qt::NoPen);
  p.drawPath(wedge);
}

}  // namespace

std::optional<Ellipse2> sigmaEllipse(const Eigen::Matrix2d& covariance, double k_sigma) {
  if (!covariance.allFinite() || !std::isfinite(k_sigma) || k_sigma < 0.0)
    return std::nullopt;
  const Eigen::Matrix2d sym = 0.5 * (covariance + covariance.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(sym);
  if (solver.info() != Eigen::Success)
    return std::nullopt;
  const Eigen::Vector2d values = solver.eigenvalues();  // ascending
  if (values(0) < -1e-12 * std::max(1.0, std::abs(values(1))))
    return std::nullopt;
  const Eigen::Vector2d major_dir = solver.eigenvectors().col(1);
  return Ellipse2{k_sigma * std::sqrt(std::max(values(1), 0.0)),
                  k_sigma * std::sqrt(std::max(values(0), 0.0)),
                  std::atan2(major_dir.y(), major_dir.x())};
}

void paintEstimatorOverlay(QPainter& p, const MapView& view, const EstimatorOverlay& overlay) {
  p.save();
  p.setRenderHint(QPainter::Antialiasing);

  // Matched features of the newest update: the wall piece or point in bold, a thin line from
  // the sensor to it (what the echo was attributed to).
  for (const MatchedFeatureMarker& m : overlay.matches) {
    const QColor colour = m.accepted ? QColor(0, 170, 170) : QColor(200, 120, 0);
    QPen pen(colour, 5.0, m.accepted ? Qt::SolidLine : Qt::DashLine, Qt::RoundCap);
    p.setPen(pen);
    p.setBrush(Qt::NoBrush);
    std::optional<irgs::Vec2> target;
    if (m.wall && m.wall->a.allFinite() && m.wall->b.allFinite()) {
      p.drawLine(view.worldToWidget(m.wall->a), view.worldToWidget(m.wall->b));
      // The foot of the perpendicular from the sensor, clamped to the piece.
      const irgs::Vec2 d = m.wall->b - m.wall->a;
      const double len2 = d.squaredNorm();
      const double t =
          len2 > 0.0 ? std::clamp((m.sensor - m.wall->a).dot(d) / len2, 0.0, 1.0) : 0.0;
      target = m.wall->a + t * d;
    } else if (m.point && m.point->allFinite()) {
      p.setBrush(colour);
      p.drawEllipse(view.worldToWidget(*m.point), 6.0, 6.0);
      target = *m.point;
    }
    if (target && m.sensor.allFinite()) {
      QPen ray(colour, 1.2, Qt::DotLine);
      p.setPen(ray);
      p.drawLine(view.worldToWidget(m.sensor), view.worldToWidget(*target));
    }
  }

  QFont font = p.font();
  font.setPointSizeF(8.5);
  font.setBold(true);
  p.setFont(font);
  for (const EstimatorPoseMarker& marker : overlay.poses) {
    if (!finitePose(marker.pose))
      continue;
    const QPointF centre = view.worldToWidget(marker.pose.position());
    if (marker.covariance && marker.covariance->allFinite()) {
      const Eigen::Matrix3d& c = *marker.covariance;
      if (const auto ellipse = sigmaEllipse(c.topLeftCorner<2, 2>(), 2.0)) {
        p.save();
        p.translate(centre);
        p.rotate(-radToDeg(ellipse->angle_rad));  // screen y points down
        QColor fill = marker.colour;
        fill.setAlpha(40);
        p.setBrush(fill);
        p.setPen(QPen(marker.colour, 1.5));
        // At least a couple of pixels so a tight ellipse stays visible.
        const double rx = std::max(ellipse->major_m * view.scale, 2.0);
        const double ry = std::max(ellipse->minor_m * view.scale, 2.0);
        p.drawEllipse(QPointF(0, 0), rx, ry);
        p.restore();
      }
      const double sigma_theta = std::sqrt(std::max(c(2, 2), 0.0));
      if (std::isfinite(sigma_theta))
        paintWedge(p, centre, marker.pose.theta, 2.0 * sigma_theta, marker.colour);
    }
    const QPointF tip = centre + QPointF(std::cos(marker.pose.theta) * kWedgeRadius_px,
                                         -std::sin(marker.pose.theta) * kWedgeRadius_px);
    p.setPen(QPen(marker.colour, 2.0, Qt::SolidLine, Qt::RoundCap));
    p.drawLine(centre, tip);
    p.setBrush(marker.colour);
    p.setPen(QPen(Qt::white, 1.0));
    p.drawEllipse(centre, kDotRadius_px, kDotRadius_px);
    if (!marker.label.isEmpty()) {
      // Label on the side away from the heading, with a halo for contrast over the map.
      const QPointF at = centre + QPointF(-std::cos(marker.pose.theta) * 14.0 - 8.0,
                                          std::sin(marker.pose.theta) * 14.0 + 4.0);
      QPainterPath text;
      text.addText(at, font, marker.label);
      p.setPen(QPen(QColor(255, 255, 255, 220), 3.0));
      p.setBrush(Qt::NoBrush);
      p.drawPath(text);
      p.setPen(Qt::NoPen);
      p.setBrush(marker.colour.darker(130));
      p.drawPath(text);
    }
  }

  if (overlay.drag_pose && finitePose(*overlay.drag_pose)) {
    const QPointF centre = view.worldToWidget(overlay.drag_pose->position());
    const QPointF tip = centre + QPointF(std::cos(overlay.drag_pose->theta) * 40.0,
                                         -std::sin(overlay.drag_pose->theta) * 40.0);
    p.setPen(QPen(QColor(120, 0, 160), 2.5, Qt::SolidLine, Qt::RoundCap));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(centre, 8.0, 8.0);
    p.drawLine(centre, tip);
  }
  p.restore();
}

}  // namespace irgs::widgets
