#pragma once
// Colours and pens of the map canvas (sRGB). Static layers are light and quiet; live data is
// saturated.

#include <QColor>
#include <QPen>

namespace irgs::widgets::palette {

inline const QColor kOutsideColour(236, 238, 242);
inline const QColor kFloorColour(252, 252, 250);
inline const QColor kMinorGridColour(232, 234, 238);
inline const QColor kMajorGridColour(212, 216, 223);
inline const QColor kWallColour(44, 49, 60);
inline const QColor kObstacleFill(196, 201, 209);
inline const QColor kObstacleOutline(112, 119, 131);
inline const QColor kCornerColour(239, 108, 0);
inline const QColor kEdgeColour(126, 87, 194);
inline const QColor kMarkerFill(229, 57, 53, 70);
inline const QColor kMarkerOutline(229, 57, 53, 130);
inline const QColor kLightFill(255, 236, 140, 110);
inline const QColor kLightOutline(214, 184, 60, 120);
inline const QColor kGraphColour(25, 118, 210, 190);
inline const QColor kGraphLabel(13, 71, 161);
inline const QColor kRobotFill(30, 136, 229, 215);
inline const QColor kRobotOutline(13, 71, 161);
inline const QColor kTruthColour(46, 160, 67);
inline const QColor kTrailColour(142, 36, 170, 150);  // purple: apart from the graph blue
inline const QColor kEchoFill(255, 152, 0, 50);
inline const QColor kEchoOutline(230, 120, 0, 150);
inline const QColor kEchoArc(216, 67, 21, 230);
inline const QColor kNoEchoFill(120, 144, 156, 28);
inline const QColor kNoEchoOutline(120, 144, 156, 110);
inline const QColor kBumperIdle(55, 60, 70, 150);
inline const QColor kBumperHit(229, 28, 35);

// A pen whose width is in device pixels whatever the painter's transform.
inline QPen cosmeticPen(const QColor& colour, double width_px, Qt::PenStyle style = Qt::SolidLine) {
  QPen pen(colour, width_px, style, Qt::RoundCap, Qt::RoundJoin);
  pen.setCosmetic(true);
  return pen;
}

}  // namespace irgs::widgets::palette
