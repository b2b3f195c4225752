#pragma once
// Human-readable console text for robot state and events. Degrees and centimetres here: this is
// the user's edge of the program.

#include <QString>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::gui {

// "(1.23, -0.45) m 37.0°"  (heading in (-180, 180])
QString formatPose(const Pose2& pose);

// The two sensor console lines, short enough for the side column:
//   "(1.23, -0.45) m 37.0°  v 0.20 m/s  ω 15°/s"   odometry pose and measured velocity
//   "sonar cm 123 >400 — 87 …"   in profile order; `latest` holds the newest reading per sonar
// (nullopt = not fired yet, "—"); no echo prints ">max" (nothing seen up to the maximum range).
QString formatPoseLine(const TelemetrySample& sample);
QString formatSonarLine(const RobotProfile& profile,
                        const std::vector<std::optional<SonarReading>>& latest);
// "Sonar order: 0 front_left_forward, 1 …" (explains formatSonarLine's columns).
QString formatSonarLegend(const RobotProfile& profile);

// Name of bumper `index` from the profile ("#3" when it has none).
QString bumperName(const RobotProfile& profile, int index);

// Lines for every bumper whose state differs between `before` and `after` (bit i = bumper i).
std::vector<QString> describeBumperChanges(const RobotProfile& profile, std::uint32_t before,
                                           std::uint32_t after);

// "10×" / "max"
QString formatSpeedFactor(double factor);

}  // namespace irgs::gui
