#pragma once
// The robot as drawn on the map canvas: its body outline (or a disc) with a heading chevron and
// bumper bars, a dashed ghost for the true pose, and its sonar cones. Holds the robot profile
// and the body polygon prepared from it.

#include <QPolygonF>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"
#include "widgets/canvas/map_view.hpp"

class QPainter;

namespace irgs::widgets {

// The latest reading of one sonar and the sample time it came with.
struct SonarState {
  irgs::SonarReading reading;
  double time_s = 0.0;  // sample time of the reading
};

class RobotPainter {
 public:
  static constexpr double kFallbackBodyRadius_m = 0.15;
  static constexpr double kMinRobotRadius_px = 7.0;  // below this: a fixed-size marker

  // Keeps the profile; an outline of fewer than 3 finite points is drawn as a disc of
  // kFallbackBodyRadius_m.
  void setProfile(const irgs::RobotProfile& profile);
  const irgs::RobotProfile& profile() const { return profile_; }
  // The radius of the body's circumscribed circle, metres.
  double bodyRadius() const;

  // Cones of the sonars with a reading no older than `stale_s` before `now_s` (telemetry
  // time): filled with an arc at the echo range, dashed to the maximum range without an echo.
  // `sonar` is indexed like the profile's sonars.
  void paintSonar(QPainter& p, const MapView& view, const irgs::Pose2& pose,
                  const std::vector<std::optional<SonarState>>& sonar, double now_s,
                  double stale_s) const;
  // The body at `pose`; `bumpers` has bit i set while bumper i is pressed. A ghost is dashed,
  // hollow and shows no bumpers.
  void paintRobot(QPainter& p, const MapView& view, const irgs::Pose2& pose, std::uint32_t bumpers,
                  bool ghost) const;

 private:
  irgs::RobotProfile profile_;
  QPolygonF body_polygon_;  // body frame
};

}  // namespace irgs::widgets
