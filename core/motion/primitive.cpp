#include "core/motion/primitive.hpp"

namespace irgs::motion {

const char* toString(PrimitiveKind kind) {
  switch (kind) {
    case PrimitiveKind::kTurn:
      return "turn";
    case PrimitiveKind::kDrive:
      return "drive";
    case PrimitiveKind::kFollowWall:
      return "follow wall";
    case PrimitiveKind::kSegments:
      return "segments";
    case PrimitiveKind::kFollowPath:
      return "follow path";
  }
  return "?";
}

const char* toString(ReportKind kind) {
  switch (kind) {
    case ReportKind::kStarted:
      return "started";
    case ReportKind::kRefused:
      return "refused";
    case ReportKind::kTurningPoint:
      return "turning point";
    case ReportKind::kDistanceMark:
      return "distance mark";
    case ReportKind::kMode:
      return "mode";
    case ReportKind::kWallLost:
      return "wall lost";
    case ReportKind::kFrontWall:
      return "wall ahead";
    case ReportKind::kContact:
      return "contact";
    case ReportKind::kDone:
      return "done";
    case ReportKind::kFailed:
      return "failed";
    case ReportKind::kCancelled:
      return "cancelled";
  }
  return "?";
}

const char* toString(Reason reason) {
  switch (reason) {
    case Reason::kNone:
      return "";
    case Reason::kInvalid:
      return "invalid specification";
    case Reason::kUnsupported:
      return "not supported by this robot";
    case Reason::kBumped:
      return "bumped";
    case Reason::kBlocked:
      return "blocked";
    case Reason::kNoProgress:
      return "no progress";
    case Reason::kSafety:
      return "safety stop";
    case Reason::kNoSensors:
      return "missing sonars";
    case Reason::kNoAnswer:
      return "no answer from the robot";
  }
  return "?";
}

}  // namespace irgs::motion
