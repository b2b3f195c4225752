#pragma once
// Vector-drawn icons of the drive pad (no image files, crisp at any device pixel ratio).

#include <QColor>
#include <QIcon>

namespace irgs::widgets {

enum class DriveIcon {
  kForward,
  kBack,
  kTurnLeft,
  kTurnRight,
  kArcForwardLeft,
  kArcForwardRight,
  kArcBackLeft,
  kArcBackRight
};

QIcon makeDriveIcon(DriveIcon icon, const QColor& colour);

}  // namespace irgs::widgets
