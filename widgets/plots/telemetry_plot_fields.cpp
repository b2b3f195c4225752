#include "widgets/plots/telemetry_plot_fields.hpp"

#include <algorithm>
#include <cmath>

namespace irgs::widgets {
namespace {

void addPose(std::vector<PlotFieldValue>& out, const QString& group, const Pose2& pose) {
  out.push_back({group + QStringLiteral("/x"), QStringLiteral("m"), pose.x});
  out.push_back({group + QStringLiteral("/y"), QStringLiteral("m"), pose.y});
  out.push_back({group + QStringLiteral("/theta"), QStringLiteral("rad"), pose.theta});
}

}  // namespace

std::vector<PlotFieldValue> telemetryPlotFields(const TelemetrySample& sample) {
  std::vector<PlotFieldValue> out;
  out.reserve(24 + sample.sonar.size() + sample.proximity_m.size());
  addPose(out, QStringLiteral("Telemetry/Odometry pose"), sample.odometry_pose);
  if (sample.true_pose)
    addPose(out, QStringLiteral("Telemetry/True pose (simulator)"), *sample.true_pose);
  out.push_back({QStringLiteral("Telemetry/Velocity/linear"), QStringLiteral("m/s"),
                 sample.measured_velocity.linear_mps});
  out.push_back({QStringLiteral("Telemetry/Velocity/angular"), QStringLiteral("rad/s"),
                 sample.measured_velocity.angular_radps});
  out.push_back({QStringLiteral("Telemetry/Encoders/left"), QStringLiteral("ticks"),
                 static_cast<double>(sample.left_ticks)});
  out.push_back({QStringLiteral("Telemetry/Encoders/right"), QStringLiteral("ticks"),
                 static_cast<double>(sample.right_ticks)});
  for (const SonarReading& reading : sample.sonar) {
    if (reading.echo) {
      out.push_back(
          {QStringLiteral("Telemetry/Sonar/range %1").arg(reading.sensor, 2, 10, QLatin1Char('0')),
           QStringLiteral("m"), reading.range_m});
    }
  }
  for (std::size_t i = 0; i < sample.proximity_m.size(); ++i) {
    out.push_back({QStringLiteral("Telemetry/Proximity/sensor %1").arg(i, 2, 10, QLatin1Char('0')),
                   QStringLiteral("m"), sample.proximity_m[i]});
  }
  if (sample.gyro) {
    out.push_back(
        {QStringLiteral("Telemetry/Gyro/rate"), QStringLiteral("rad/s"), sample.gyro->rate_radps});
    out.push_back({QStringLiteral("Telemetry/Gyro/temperature"), QStringLiteral("°C"),
                   sample.gyro->temperature_c});
    out.push_back({QStringLiteral("Telemetry/Gyro/saturated"), QStringLiteral("0/1"),
                   sample.gyro->saturated ? 1.0 : 0.0});
  }
  out.push_back({QStringLiteral("Telemetry/Contact/bumpers"), QStringLiteral("bits"),
                 static_cast<double>(sample.bumpers)});
  out.push_back({QStringLiteral("Telemetry/Contact/drive stalled"), QStringLiteral("0/1"),
                 sample.drive_stalled ? 1.0 : 0.0});
  return out;
}

std::vector<PlotFieldValue> estimatorPlotFields(const EstimatorStep& step) {
  std::vector<PlotFieldValue> out;
  addPose(out, QStringLiteral("Estimator/Estimate"), step.estimate);
  const LocCov& p = step.covariance;
  out.push_back({QStringLiteral("Estimator/Sigma/x"), QStringLiteral("m"),
                 std::sqrt(std::max(p(0, 0), 0.0))});
  out.push_back({QStringLiteral("Estimator/Sigma/y"), QStringLiteral("m"),
                 std::sqrt(std::max(p(1, 1), 0.0))});
  out.push_back({QStringLiteral("Estimator/Sigma/theta"), QStringLiteral("rad"),
                 std::sqrt(std::max(p(2, 2), 0.0))});
  addPose(out, QStringLiteral("Estimator/Dead reckoning"), step.dead_reckoning);
  if (step.error) {
    const LocState& e = *step.error;
    out.push_back({QStringLiteral("Estimator/Error/x"), QStringLiteral("m"), e(0)});
    out.push_back({QStringLiteral("Estimator/Error/y"), QStringLiteral("m"), e(1)});
    out.push_back({QStringLiteral("Estimator/Error/theta"), QStringLiteral("rad"), e(2)});
    out.push_back(
        {QStringLiteral("Estimator/Error/position"), QStringLiteral("m"), std::hypot(e(0), e(1))});
  }
  if (step.nees)
    out.push_back({QStringLiteral("Estimator/Error/NEES"), QString(), *step.nees});
  if (!step.readings.empty()) {
    const auto accepted = std::count_if(step.readings.begin(), step.readings.end(),
                                        [](const StereoReadingRecord& r) { return r.accepted; });
    out.push_back({QStringLiteral("Estimator/Stereo/accepted readings"), QStringLiteral("count"),
                   static_cast<double>(accepted)});
  }
  return out;
}

}  // namespace irgs::widgets
