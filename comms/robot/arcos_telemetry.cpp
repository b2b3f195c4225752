#include "comms/robot/arcos_telemetry.hpp"

#include <cmath>

namespace irgs::comms {

namespace {

std::int64_t signed15(std::uint16_t raw) {
  const std::int64_t v = raw & 0x7FFF;
  return v >= 0x4000 ? v - 0x8000 : v;
}

}  // namespace

std::vector<int> arcosBumperBits(const RobotProfile& profile) {
  std::vector<int> bits;
  int front = 0;
  int rear = 0;
  for (const BumperSpec& b : profile.bumpers) {
    const bool is_front = std::cos(b.normal_rad) >= 0.0;
    int& slot = is_front ? front : rear;
    bits.push_back(slot < 7 ? (is_front ? 9 : 1) + slot : -1);
    ++slot;
  }
  return bits;
}

ArcosTelemetryConverter::ArcosTelemetryConverter(RobotProfile profile, ArcosParams params)
    : profile_(std::move(profile)), params_(std::move(params)) {
  bumper_bits_ = arcosBumperBits(profile_);
}

void ArcosTelemetryConverter::reset() {
  x_.reset();
  y_.reset();
  started_ = false;
  if (anchor_ && last_pose_)
    anchor_ = last_pose_;  // continue where the robot was last seen
}

TelemetrySample ArcosTelemetryConverter::convert(const arcos::StandardSip& sip, double time_s) {
  const bool first = !started_;
  if (!started_) {
    x0_ = signed15(sip.x_raw);
    y0_ = signed15(sip.y_raw);
    started_ = true;
  }
  const double x_units = static_cast<double>(x0_ + x_.update(sip.x_raw));
  const double y_units = static_cast<double>(y0_ + y_.update(sip.y_raw));
  TelemetrySample s;
  s.time_s = time_s;
  const Pose2 raw{x_units * params_.dist_conv_mm / 1000.0, y_units * params_.dist_conv_mm / 1000.0,
                  wrapAngle(sip.theta_raw * params_.angle_conv_rad)};
  if (anchor_ && first) {
    // to_map ⊕ raw = anchor: to_map = anchor ⊕ raw^-1.
    const double c = std::cos(raw.theta), sn = std::sin(raw.theta);
    const Pose2 raw_inverse{-(c * raw.x + sn * raw.y), sn * raw.x - c * raw.y, -raw.theta};
    to_map_ = anchor_->compose(raw_inverse);
  }
  s.odometry_pose = to_map_.compose(raw);
  last_pose_ = s.odometry_pose;
  const double left_mmps = sip.left_velocity * params_.vel_conv_mmps;
  const double right_mmps = sip.right_velocity * params_.vel_conv_mmps;
  s.measured_velocity.linear_mps = 0.5 * (left_mmps + right_mmps) / 1000.0;
  s.measured_velocity.angular_radps = sip.rotational_velocity
                                          ? degToRad(*sip.rotational_velocity / 10.0)
                                          : 0.5 * (right_mmps - left_mmps) * params_.diff_conv;
  for (const arcos::SonarRangeRaw& r : sip.sonars) {
    if (r.index >= profile_.sonars.size()) {
      ++skipped_sonars_;
      continue;
    }
    const SonarSpec& spec = profile_.sonars[r.index];
    const double range_m = r.range * params_.range_conv_mm / 1000.0;
    const bool echo = range_m > 0.0 && range_m < spec.max_range_m - 1e-6;
    s.sonar.push_back({static_cast<int>(r.index), echo ? range_m : spec.max_range_m, echo});
  }
  s.drive_stalled = sip.leftStalled() || sip.rightStalled();
  for (std::size_t i = 0; i < bumper_bits_.size() && i < 32; ++i) {
    if (bumper_bits_[i] >= 0 && ((sip.stall_and_bumpers >> bumper_bits_[i]) & 1u) != 0)
      s.bumpers |= 1u << i;
  }
  return s;
}

}  // namespace irgs::comms
