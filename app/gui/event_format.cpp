#include "app/gui/event_format.hpp"

#include <QStringList>
#include <cmath>

namespace irgs::gui {

namespace {

// Heading in degrees for display, in (-180, 180], where rounding to 0.1° cannot print "-180.0".
double displayHeading_deg(double theta_rad) {
  const double deg = radToDeg(wrapAngle(theta_rad));
  return deg <= -179.95 ? deg + 360.0 : deg;
}

// Rounds away the sign of values that print as zero ("-0.00" reads as a fault).
double tidy(double value, int decimals) {
  return std::abs(value) < 0.5 * std::pow(10.0, -decimals) ? 0.0 : value;
}

}  // namespace

QString formatPose(const Pose2& pose) {
  return QStringLiteral("(%1, %2) m %3°")
      .arg(tidy(pose.x, 2), 0, 'f', 2)
      .arg(tidy(pose.y, 2), 0, 'f', 2)
      .arg(tidy(displayHeading_deg(pose.theta), 1), 0, 'f', 1);
}

QString formatPoseLine(const TelemetrySample& sample) {
  return QStringLiteral("%1  v %2 m/s  ω %3°/s")
      .arg(formatPose(sample.odometry_pose))
      .arg(tidy(sample.measured_velocity.linear_mps, 2), 0, 'f', 2)
      .arg(tidy(radToDeg(sample.measured_velocity.angular_radps), 0), 0, 'f', 0);
}

QString formatSonarLine(const RobotProfile& profile,
                        const std::vector<std::optional<SonarReading>>& latest) {
  QStringList ranges;
  for (std::size_t i = 0; i < profile.sonars.size(); ++i) {
    QString value = QStringLiteral("—");
    if (i < latest.size() && latest[i]) {
      value = latest[i]->echo
                  ? QString::number(std::lround(latest[i]->range_m * 100.0))
                  : QStringLiteral(">%1").arg(std::lround(profile.sonars[i].max_range_m * 100.0));
    }
    ranges << value;
  }
  return QStringLiteral("sonar cm ") + ranges.join(QLatin1Char(' '));
}

QString formatSonarLegend(const RobotProfile& profile) {
  QStringList names;
  for (std::size_t i = 0; i < profile.sonars.size(); ++i) {
    const std::string& name = profile.sonars[i].name;
    names << QStringLiteral("%1 %2").arg(i).arg(name.empty() ? QStringLiteral("(unnamed)")
                                                             : QString::fromStdString(name));
  }
  return QStringLiteral("Sonar order in the sensor lines: ") + names.join(QStringLiteral(", "));
}

QString bumperName(const RobotProfile& profile, int index) {
  if (index >= 0 && static_cast<std::size_t>(index) < profile.bumpers.size() &&
      !profile.bumpers[static_cast<std::size_t>(index)].name.empty())
    return QString::fromStdString(profile.bumpers[static_cast<std::size_t>(index)].name);
  return QStringLiteral("#%1").arg(index);
}

std::vector<QString> describeBumperChanges(const RobotProfile& profile, std::uint32_t before,
                                           std::uint32_t after) {
  std::vector<QString> lines;
  const std::uint32_t changed = before ^ after;
  for (int i = 0; i < 32; ++i) {
    const std::uint32_t bit = std::uint32_t{1} << i;
    if ((changed & bit) == 0)
      continue;
    lines.push_back(QStringLiteral("Bumper %1 %2")
                        .arg(bumperName(profile, i), (after & bit) != 0
                                                         ? QStringLiteral("pressed")
                                                         : QStringLiteral("released")));
  }
  return lines;
}

QString formatSpeedFactor(double factor) {
  if (factor <= 0.0)
    return QStringLiteral("max");
  return QString::number(factor, 'g', 3) + QStringLiteral("×");
}

}  // namespace irgs::gui
