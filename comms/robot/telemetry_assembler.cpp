#include "comms/robot/telemetry_assembler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "comms/mavlink/messages.hpp"

namespace irgs::comms {

namespace mav = mavlink;

namespace {

std::int64_t usToMs(std::uint64_t us) {
  return static_cast<std::int64_t>((us + 500u) / 1000u);
}

// Yaw of a (w, x, y, z) quaternion: the rotation about z, whatever roll and pitch are.
double quaternionYaw(const std::array<float, 4>& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

// IRGS_MOUSE_STATUS -> MouseStatus; an unknown state is taken as "lifted" (counts not trusted).
MouseStatus mouseStatus(std::uint8_t wire) {
  switch (static_cast<mav::IrgsMouseStatus>(wire)) {
    case mav::IrgsMouseStatus::kTracking:
      return MouseStatus::kTracking;
    case mav::IrgsMouseStatus::kSaturated:
      return MouseStatus::kSaturated;
    case mav::IrgsMouseStatus::kLifted:
      break;
  }
  return MouseStatus::kLifted;
}

bool finite(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

TelemetryAssembler::TelemetryAssembler(RobotProfile profile, TelemetryAssemblerConfig config)
    : profile_(std::move(profile)), config_(config) {
  if (!std::isfinite(config_.hold_s) || config_.hold_s <= 0.0)
    throw std::invalid_argument("TelemetryAssembler: hold_s must be finite and > 0");
  if (!std::isfinite(config_.max_gyro_age_s) || config_.max_gyro_age_s < 0.0)
    throw std::invalid_argument("TelemetryAssembler: max_gyro_age_s must be finite and >= 0");
  carried_.proximity_m.reserve(profile_.proximity.size());
  for (const ProximitySpec& spec : profile_.proximity)
    carried_.proximity_m.push_back(spec.max_range_m);  // nothing seen until told otherwise
}

bool TelemetryAssembler::advanceTo(std::int64_t time_ms, bool is_pose) {
  const bool restarted_after_reset =
      clock_in_doubt_ && is_pose && released_ms_ && time_ms < *released_ms_;
  if (is_pose)
    clock_in_doubt_ = false;
  if (restarted_after_reset || (newest_ms_ && time_ms < *newest_ms_ - kRestartJump_ms)) {
    ++counters_.restarts;  // the robot's boot clock started over
    current_ = {};
    newest_ms_.reset();
    released_ms_.reset();
  }
  newest_ms_ = std::max(newest_ms_.value_or(time_ms), time_ms);
  if (is_pose && released_ms_ && time_ms <= *released_ms_) {
    ++counters_.stale_poses;  // another pose message for a sample already released
    return false;
  }
  if (!current_.time_ms) {
    current_.time_ms = time_ms;
    return true;
  }
  const std::int64_t current = *current_.time_ms;
  if (time_ms > current) {
    // The next time step has begun: what we have for `current` is all there will be.
    if (current_.has_xy || current_.has_theta) {
      if (!(current_.has_xy && current_.has_theta) && last_pose_) {
        // Half a pose (e.g. LOCAL_POSITION_NED without its ATTITUDE): complete it from the
        // previous sample rather than losing the readings' pose.
        const Pose2& last = *last_pose_;
        if (!current_.has_xy) {
          current_.sample.odometry_pose.x = last.x;
          current_.sample.odometry_pose.y = last.y;
        }
        if (!current_.has_theta)
          current_.sample.odometry_pose.theta = last.theta;
        current_.has_xy = current_.has_theta = true;
      }
      if (current_.has_xy && current_.has_theta) {
        release();
      } else {
        current_.has_xy = current_.has_theta = false;  // no reference pose: keep the readings
        current_.has_velocity = current_.has_omega = current_.has_ned_velocity = false;
      }
    }
    current_.time_ms = time_ms;
    return true;
  }
  if (time_ms < current && is_pose) {
    ++counters_.stale_poses;
    return false;
  }
  return true;  // same time stamp, or an older reading that joins this sample
}

bool TelemetryAssembler::poseAlreadyComplete() {
  // The firmware may send one pose in several messages (ODOMETRY and LOCAL_POSITION_NED +
  // ATTITUDE carry the same pose at float precision, differently rounded). The first complete
  // pose of a time step is the sample's: which one that is depends only on the byte stream,
  // never on when the hold timer released the sample, so a replay of the recorded bytes
  // reproduces the live samples exactly.
  if (!(current_.has_xy && current_.has_theta))
    return false;
  ++counters_.duplicate_poses;
  return true;
}

void TelemetryAssembler::poseUpdated(double now_s) {
  if (!(current_.has_xy && current_.has_theta))
    return;
  if (!current_.complete_since_s)
    current_.complete_since_s = now_s;
  if (config_.release_on_pose)
    release();
}

void TelemetryAssembler::release() {
  flushLate();
  released_by_hold_ = false;
  TelemetrySample sample = std::move(current_.sample);
  sample.time_s = static_cast<double>(current_.time_ms.value_or(0)) * 1e-3;
  sample.odometry_pose.theta = wrapAngle(sample.odometry_pose.theta);
  if (!current_.has_velocity && current_.has_ned_velocity) {
    // NED velocity projected on the heading: v = vx cos(yaw) + vy sin(yaw), yaw = -theta.
    const double th = sample.odometry_pose.theta;
    sample.measured_velocity.linear_mps =
        current_.ned_vx * std::cos(th) - current_.ned_vy * std::sin(th);
  }
  sample.left_ticks = carried_.left_ticks;
  sample.right_ticks = carried_.right_ticks;
  sample.mouse = carried_.mouse;
  sample.casters = carried_.casters;
  sample.bumpers = carried_.bumpers;
  sample.proximity_m = carried_.proximity_m;
  attachGyro(sample);
  counters_.sonar_readings += sample.sonar.size();
  ++counters_.samples;
  released_ms_ = current_.time_ms;
  last_pose_ = sample.odometry_pose;
  last_velocity_ = sample.measured_velocity;
  ready_.push_back(std::move(sample));
  current_ = {};
}

void TelemetryAssembler::attachGyro(TelemetrySample& sample) const {
  if (!gyro_)
    return;
  const double age_s = sample.time_s - static_cast<double>(gyro_ms_) * 1e-3;
  if (age_s >= -1e-9 && age_s <= config_.max_gyro_age_s + 1e-9)
    sample.gyro = gyro_;
}

bool TelemetryAssembler::belongsToHeldRelease(std::int64_t time_ms) const {
  return released_by_hold_ && released_ms_ && time_ms <= *released_ms_ && !current_.time_ms &&
         time_ms >= *released_ms_ - kRestartJump_ms;
}

void TelemetryAssembler::addLateReading(const SonarReading& reading) {
  if (reading.sensor < 0 || static_cast<std::size_t>(reading.sensor) >= profile_.sonars.size()) {
    ++counters_.ignored_readings;
    return;
  }
  const double released_s = static_cast<double>(*released_ms_) * 1e-3;
  if (!ready_.empty() && ready_.back().time_s == released_s) {
    ready_.back().sonar.push_back(reading);  // the held sample is not taken yet: join it
    ++counters_.sonar_readings;
    return;
  }
  if (!late_) {
    late_ = TelemetrySample{};
    late_->time_s = released_s;
    late_->odometry_pose = last_pose_.value_or(Pose2{});
    late_->measured_velocity = last_velocity_;
  }
  late_->sonar.push_back(reading);
}

void TelemetryAssembler::flushLate() {
  if (!late_)
    return;
  TelemetrySample sample = std::move(*late_);
  late_.reset();
  sample.left_ticks = carried_.left_ticks;
  sample.right_ticks = carried_.right_ticks;
  sample.mouse = carried_.mouse;
  sample.casters = carried_.casters;
  sample.bumpers = carried_.bumpers;
  sample.proximity_m = carried_.proximity_m;
  attachGyro(sample);
  counters_.sonar_readings += sample.sonar.size();
  ++counters_.late_samples;
  ready_.push_back(std::move(sample));
}

void TelemetryAssembler::addReading(const SonarReading& reading) {
  if (reading.sensor < 0 || static_cast<std::size_t>(reading.sensor) >= profile_.sonars.size()) {
    ++counters_.ignored_readings;
    return;
  }
  if (!current_.has_xy && current_.sample.sonar.size() >= config_.max_unposed_readings) {
    ++counters_.ignored_readings;
    return;
  }
  current_.sample.sonar.push_back(reading);
}

void TelemetryAssembler::onLocalPosition(const mav::Frame& frame, double now_s) {
  const auto lp = frame.as<mav::LocalPositionNed>();
  if (!lp || !finite({lp->x, lp->y, lp->vx, lp->vy}))
    return;
  if (!advanceTo(lp->time_boot_ms, true) || poseAlreadyComplete())
    return;
  // NED (world x as north) -> ours: the rotation by pi about x flips y.
  current_.sample.odometry_pose.x = lp->x;
  current_.sample.odometry_pose.y = -static_cast<double>(lp->y);
  current_.ned_vx = lp->vx;
  current_.ned_vy = lp->vy;
  current_.has_ned_velocity = true;
  current_.has_xy = true;
  poseUpdated(now_s);
}

void TelemetryAssembler::onFrame(const mav::Frame& frame, double now_s) {
  switch (frame.message_id) {
    case mav::LocalPositionNed::kId:
      onLocalPosition(frame, now_s);
      break;
    case mav::Attitude::kId: {
      const auto att = frame.as<mav::Attitude>();
      if (!att || !finite({att->yaw, att->yawspeed}) || !advanceTo(att->time_boot_ms, true) ||
          poseAlreadyComplete())
        return;
      current_.sample.odometry_pose.theta = wrapAngle(-static_cast<double>(att->yaw));
      current_.sample.measured_velocity.angular_radps = -static_cast<double>(att->yawspeed);
      current_.has_theta = current_.has_omega = true;
      poseUpdated(now_s);
      break;
    }
    case mav::Odometry::kId: {
      const auto od = frame.as<mav::Odometry>();
      if (!od || !finite({od->x, od->y, od->q[0], od->q[1], od->q[2], od->q[3], od->vx, od->vy,
                          od->yawspeed}))
        return;
      const auto pose_frame = static_cast<mav::MavFrame>(od->frame_id);
      // z-down local frames (NED, FRD) flip y and yaw; FLU is our own convention.
      double flip = 0.0;
      if (pose_frame == mav::MavFrame::kLocalNed || pose_frame == mav::MavFrame::kLocalFrd)
        flip = -1.0;
      else if (pose_frame == mav::MavFrame::kLocalFlu)
        flip = 1.0;
      if (flip == 0.0) {
        ++counters_.unsupported_frames;
        return;
      }
      if (!advanceTo(usToMs(od->time_usec), true) || poseAlreadyComplete())
        return;
      const double theta = wrapAngle(flip * quaternionYaw(od->q));
      current_.sample.odometry_pose = Pose2{od->x, flip * od->y, theta};
      const auto twist_frame = static_cast<mav::MavFrame>(od->child_frame_id);
      if (twist_frame == pose_frame) {
        // Velocity in the local frame: project it on the heading.
        const double vy = flip * od->vy;
        current_.sample.measured_velocity.linear_mps =
            od->vx * std::cos(theta) + vy * std::sin(theta);
      } else {
        current_.sample.measured_velocity.linear_mps = od->vx;  // body frame: vx is forward
      }
      // A body z axis points down in FRD and in NED-aligned local frames (yaw clockwise).
      current_.sample.measured_velocity.angular_radps = flip * od->yawspeed;
      current_.has_xy = current_.has_theta = current_.has_velocity = current_.has_omega = true;
      poseUpdated(now_s);
      break;
    }
    case mav::IrgsPose2d::kId: {
      const auto p = frame.as<mav::IrgsPose2d>();
      if (!p || !finite({p->x, p->y, p->theta, p->v, p->omega}) ||
          !advanceTo(p->time_boot_ms, true) || poseAlreadyComplete())
        return;
      current_.sample.odometry_pose = Pose2{p->x, p->y, wrapAngle(p->theta)};
      current_.sample.measured_velocity = {p->v, p->omega};
      current_.has_xy = current_.has_theta = current_.has_velocity = current_.has_omega = true;
      poseUpdated(now_s);
      break;
    }
    case mav::DistanceSensor::kId: {
      const auto ds = frame.as<mav::DistanceSensor>();
      if (!ds)
        return;
      const bool late = belongsToHeldRelease(ds->time_boot_ms);
      if (!late)
        advanceTo(ds->time_boot_ms, false);
      SonarReading r;
      r.sensor = ds->id;
      if (ds->current_distance == 0) {  // not a measurement (some sensors report 0 for none)
        ++counters_.ignored_readings;
        return;
      }
      // Beyond max_distance (the firmware sends max_distance + 1; UINT16_MAX is "unknown"):
      // nothing seen up to the sensor's maximum range.
      r.echo = ds->current_distance <= ds->max_distance &&
               ds->current_distance != std::numeric_limits<std::uint16_t>::max();
      if (r.echo)
        r.range_m = ds->current_distance * 0.01;
      else if (static_cast<std::size_t>(r.sensor) < profile_.sonars.size())
        r.range_m = profile_.sonars[static_cast<std::size_t>(r.sensor)].max_range_m;
      if (late)
        addLateReading(r);
      else
        addReading(r);
      break;
    }
    case mav::IrgsSonarScan::kId: {
      const auto scan = frame.as<mav::IrgsSonarScan>();
      if (!scan)
        return;
      const bool late = belongsToHeldRelease(scan->time_boot_ms);
      if (!late)
        advanceTo(scan->time_boot_ms, false);
      const std::size_t count = std::min<std::size_t>(scan->count, scan->range.size());
      for (std::size_t i = 0; i < count; ++i) {
        if (((scan->fired >> i) & 1u) == 0)
          continue;  // not fired since the previous scan: its range is not fresh
        SonarReading r;
        r.sensor = static_cast<int>(i);
        r.echo = scan->range[i] != std::numeric_limits<std::uint16_t>::max();
        if (r.echo)
          r.range_m = scan->range[i] * 0.001;
        else if (i < profile_.sonars.size())
          r.range_m = profile_.sonars[i].max_range_m;
        if (late)
          addLateReading(r);
        else
          addReading(r);
      }
      break;
    }
    case mav::IrgsEncoderTicks::kId: {
      const auto ticks = frame.as<mav::IrgsEncoderTicks>();
      if (!ticks)
        return;
      if (!belongsToHeldRelease(usToMs(ticks->time_usec)))
        advanceTo(usToMs(ticks->time_usec), false);
      carried_.left_ticks = ticks->left_ticks;
      carried_.right_ticks = ticks->right_ticks;
      break;
    }
    case mav::IrgsMouseCounts::kId: {
      const auto m = frame.as<mav::IrgsMouseCounts>();
      if (!m)
        return;
      if (!belongsToHeldRelease(usToMs(m->time_usec)))
        advanceTo(usToMs(m->time_usec), false);
      MouseReading reading;
      reading.right = {m->right_x, m->right_y, mouseStatus(m->right_status)};
      reading.left = {m->left_x, m->left_y, mouseStatus(m->left_status)};
      carried_.mouse = reading;
      ++counters_.mouse_frames;
      break;
    }
    case mav::IrgsCasterEncoders::kId: {
      const auto c = frame.as<mav::IrgsCasterEncoders>();
      if (!c)
        return;
      if (!belongsToHeldRelease(usToMs(c->time_usec)))
        advanceTo(usToMs(c->time_usec), false);
      CasterEncoders encoders;
      for (std::size_t i = 0; i < 3; ++i) {
        encoders.drive_ticks[i] = c->drive[i];
        encoders.steering_ticks[i] = c->steering[i];
      }
      const bool residual =
          (c->flags & static_cast<std::uint8_t>(mav::IrgsCasterFlags::kResidualValid)) != 0;
      if (residual && std::isfinite(c->residual_sum) && c->residual_sum >= 0.0) {
        encoders.residual_sum_rad = c->residual_sum;
        encoders.residual_periods = c->residual_periods;
      }
      carried_.casters = encoders;
      ++counters_.caster_frames;
      break;
    }
    case mav::ScaledImu::kId: {
      const auto imu = frame.as<mav::ScaledImu>();
      if (!imu)
        return;
      // Like the ticks: a newer time stamp first releases the step before it, so the reading
      // rides on its own step and every later one (zero-order hold).
      if (!belongsToHeldRelease(imu->time_boot_ms))
        advanceTo(imu->time_boot_ms, false);
      GyroReading reading;
      reading.rate_radps = -static_cast<double>(imu->zgyro) * 1e-3;  // FRD z down -> ours up
      if (imu->temperature != 0)
        reading.temperature_c = static_cast<double>(imu->temperature) * 0.01;
      reading.saturated = imu->zgyro == std::numeric_limits<std::int16_t>::max() ||
                          imu->zgyro <= -std::numeric_limits<std::int16_t>::max();
      gyro_ = reading;
      gyro_ms_ = imu->time_boot_ms;
      ++counters_.gyro_readings;
      break;
    }
    case mav::IrgsContact::kId: {
      const auto contact = frame.as<mav::IrgsContact>();
      if (!contact)
        return;
      if (!belongsToHeldRelease(contact->time_boot_ms))
        advanceTo(contact->time_boot_ms, false);
      carried_.bumpers = contact->bumpers;
      const std::size_t count = std::min<std::size_t>(
          {contact->proximity_count, contact->proximity.size(), profile_.proximity.size()});
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint16_t mm = contact->proximity[i];
        carried_.proximity_m[i] = mm == std::numeric_limits<std::uint16_t>::max()
                                      ? profile_.proximity[i].max_range_m
                                      : mm * 0.001;
      }
      break;
    }
    default:
      break;
  }
}

void TelemetryAssembler::tick(double now_s) {
  flushLate();  // a step's late readings arrive together; the next tick sends them on
  if (current_.has_xy && current_.has_theta && current_.complete_since_s &&
      now_s - *current_.complete_since_s >= config_.hold_s) {
    release();
    released_by_hold_ = !config_.release_on_pose;
  }
}

void TelemetryAssembler::reset() {
  if (current_.has_xy && current_.has_theta)
    release();
  flushLate();
  released_by_hold_ = false;
  current_ = {};
  clock_in_doubt_ = true;
}

std::vector<TelemetrySample> TelemetryAssembler::takeReady() {
  std::vector<TelemetrySample> out;
  out.swap(ready_);
  return out;
}

}  // namespace irgs::comms
