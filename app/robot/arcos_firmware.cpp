#include "app/robot/arcos_firmware.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "comms/arcos/arcos_commands.hpp"
#include "comms/arcos/arcos_sip.hpp"

namespace irgs::app {

namespace arcos = comms::arcos;
using arcos::Command;

namespace {

constexpr double kHeadingGain = 3.0;                    // 1/s, HEAD/DHEAD proportional control
constexpr double kHeadingDeadband_rad = degToRad(0.5);  // "heading reached"
constexpr double kMoveDone_m = 0.005;
constexpr std::uint8_t kBatteryDecivolts = 125;  // a charged 12 V lead-acid pack

std::int16_t clampInt16(double v) {
  const double r = std::round(v);
  return static_cast<std::int16_t>(std::clamp(r, -32768.0, 32767.0));
}

bool isCommand(std::uint8_t number, Command c) {
  return number == static_cast<std::uint8_t>(c);
}

}  // namespace

ArcosFirmware::ArcosFirmware(Simulator sim, ArcosFirmwareConfig config)
    : sim_(std::move(sim)), config_(std::move(config)) {
  params_ = comms::arcosParamsFromProfile(sim_.profile()).params;
  sip_period_s_ = config_.sip_period_s.value_or(params_.sip_cycle_s);
  watchdog_s_ = config_.watchdog_s.value_or(params_.watchdog_s);
  if (!(sip_period_s_ > 0.0) || !(watchdog_s_ > 0.0) || !std::isfinite(sip_period_s_) ||
      !std::isfinite(watchdog_s_))
    throw std::invalid_argument("ArcosFirmware: SIP period and watchdog must be > 0");
  motors_enabled_ = config_.motors_enabled_at_start;
  sonar_cycle_m_.resize(std::min(sim_.profile().sonars.size(), arcos::kMaxSonars));
  origin_ = sim_.odometryPose();
}

Pose2 ArcosFirmware::reportedPose() const {
  const Pose2& odom = sim_.odometryPose();
  const Vec2 p = origin_.toBody(odom.position());
  return {p.x(), p.y(), wrapAngle(odom.theta - origin_.theta)};
}

void ArcosFirmware::receiveBytes(std::span<const std::uint8_t> bytes, double now_s,
                                 std::optional<double> earliest_s) {
  packets_.clear();
  stats_.packets += decoder_.feed(bytes, packets_);
  // Over a serial line the packets of one read arrived one after the other, the last one now.
  // A reader that read late (earliest_s: the bytes may have come any time since) cannot tell
  // when they arrived: they are spread over that window, so a command is lost for coming too
  // soon only when it certainly did, not because the emulator itself was not scheduled.
  const double byte_s = config_.link_baud ? 10.0 / *config_.link_baud : 0.0;
  const auto wire_s = [&](std::size_t i) {
    return static_cast<double>(packets_[i].size + arcos::kOverhead) * byte_s;
  };
  const double even_gap_s =
      earliest_s && !packets_.empty()
          ? std::max(0.0, now_s - *earliest_s) / static_cast<double>(packets_.size())
          : 0.0;
  std::vector<double>& arrivals = arrival_scratch_;
  arrivals.assign(packets_.size(), now_s);
  for (std::size_t i = packets_.size(); i-- > 1;)
    arrivals[i - 1] = arrivals[i] - std::max(wire_s(i), even_gap_s);
  for (std::size_t i = 0; i < packets_.size(); ++i) {
    // A serial line never delivers a packet before the previous one plus its own wire time:
    // closer than that, a bridge or a late read bunched them (also across reads).
    if (byte_s > 0.0 && last_arrival_s_)
      arrivals[i] = std::max(arrivals[i], *last_arrival_s_ + wire_s(i));
    last_arrival_s_ = arrivals[i];
    onPacket(packets_[i].payload(), arrivals[i]);
  }
}

void ArcosFirmware::reply(std::span<const std::uint8_t> payload) {
  const std::vector<std::uint8_t> packet = arcos::framePacket(payload);
  output_.insert(output_.end(), packet.begin(), packet.end());
}

void ArcosFirmware::onPacket(std::span<const std::uint8_t> payload, double now_s) {
  const bool open = state_ == ArcosServerState::kOpen;
  if (open) {
    command_rate_.record(now_s);
    stats_.peak_commands_per_s = command_rate_.peak();
  }
  const arcos::CommandParseResult parsed = arcos::parseCommand(payload);
  if (!parsed.command || (config_.strict && payload.size() + 2 > kStrictMaxByteCount)) {
    ++stats_.bad_commands;
    return;
  }
  const std::uint8_t number = parsed.command->command;
  if (!open) {
    onHandshake(number, now_s);
    return;
  }
  if (config_.strict) {
    if (last_taken_s_ && now_s - *last_taken_s_ < kStrictCommandSpacing_s) {
      ++stats_.too_soon;  // the command processor was still busy with the previous one
      return;
    }
    last_taken_s_ = now_s;
    watchdog_tripped_ = false;  // any command revives the robot on its old set points
  }
  ++stats_.commands;
  last_command_s_ = now_s;
  onCommand(number, parsed.command->int_argument, now_s);
}

void ArcosFirmware::onHandshake(std::uint8_t number, double now_s) {
  // The handshake: each SYNC is echoed once the previous one was; SYNC0 always restarts it.
  const std::uint8_t echo[1] = {number};
  if (number == arcos::kPulse) {
    reply(echo);
    state_ = ArcosServerState::kWaitSync1;
  } else if (number == 1 &&
             (state_ == ArcosServerState::kWaitSync1 || state_ == ArcosServerState::kWaitSync2)) {
    reply(echo);
    state_ = ArcosServerState::kWaitSync2;
  } else if (number == 2 && state_ == ArcosServerState::kWaitSync2) {
    reply(arcos::encodeSync2Reply(
        {config_.name, config_.robot_class, config_.subclass.value_or(params_.subclass)}));
    state_ = ArcosServerState::kSynced;
  } else if (number == arcos::kOpen && state_ == ArcosServerState::kSynced) {
    state_ = ArcosServerState::kOpen;
    ++stats_.opens;
    last_command_s_ = now_s;
    last_taken_s_ = now_s;
    watchdog_tripped_ = false;
    next_sip_s_ = sim_.time_s();
    for (auto& r : sonar_cycle_m_)
      r.reset();
  } else if (number == arcos::kClose && state_ == ArcosServerState::kSynced) {
    state_ = ArcosServerState::kWaitSync0;
  }
}

void ArcosFirmware::onCommand(std::uint8_t number, std::optional<int> argument, double /*now_s*/) {
  const int arg = argument.value_or(0);
  const bool motion = isCommand(number, Command::kVel) || isCommand(number, Command::kRVel) ||
                      isCommand(number, Command::kVel2) || isCommand(number, Command::kHead) ||
                      isCommand(number, Command::kDHead) || isCommand(number, Command::kMove);
  if (motion) {
    if (!motors_enabled_)
      return;                   // ARCOS ignores motion commands while the motors are disabled
    watchdog_tripped_ = false;  // lenient mode: the watchdog cleared the set points
  }
  if (number == arcos::kPulse) {
    return;
  } else if (number == arcos::kClose) {
    stopMotion(true);
    state_ = ArcosServerState::kWaitSync0;
  } else if (isCommand(number, Command::kEnable)) {
    motors_enabled_ = arg != 0;
    if (!motors_enabled_)
      stopMotion(true);
  } else if (isCommand(number, Command::kSetO)) {
    // A heading set point keeps pointing the same way in the world: re-express it.
    if (heading_mode_ == Heading::kTarget)
      heading_target_rad_ = wrapAngle(heading_target_rad_ - reportedPose().theta);
    origin_ = sim_.odometryPose();
  } else if (isCommand(number, Command::kVel)) {
    move_remaining_m_.reset();
    velocity_mps_ = arg / 1000.0;
  } else if (isCommand(number, Command::kMove)) {
    move_remaining_m_ = arg / 1000.0;
    move_last_pose_ = sim_.odometryPose();
    velocity_mps_ = 0.0;
  } else if (isCommand(number, Command::kSetV)) {
    if (arg > 0)
      move_speed_mps_ = arg / 1000.0;  // the speed of position moves (MOVE)
  } else if (isCommand(number, Command::kRVel)) {
    heading_mode_ = Heading::kRate;
    rot_velocity_radps_ = degToRad(arg);
  } else if (isCommand(number, Command::kVel2)) {
    // Wheel speeds in Vel2Divisor mm/s units; the body velocity follows the drive kinematics.
    const arcos::WheelUnits wheels = arcos::splitVel2Argument(arg);
    const double left = wheels.left * params_.vel2_divisor / 1000.0;
    const double right = wheels.right * params_.vel2_divisor / 1000.0;
    move_remaining_m_.reset();
    velocity_mps_ = 0.5 * (left + right);
    heading_mode_ = Heading::kRate;
    rot_velocity_radps_ = (right - left) / sim_.profile().drive.wheelbase_m;
  } else if (isCommand(number, Command::kHead)) {
    heading_mode_ = Heading::kTarget;
    heading_target_rad_ = wrapAngle(degToRad(arg));
  } else if (isCommand(number, Command::kDHead)) {
    heading_mode_ = Heading::kTarget;
    heading_target_rad_ = wrapAngle(reportedPose().theta + degToRad(arg));
  } else if (isCommand(number, Command::kSonar)) {
    sonar_enabled_ = arg != 0;
    for (auto& r : sonar_cycle_m_)
      r.reset();
  } else if (isCommand(number, Command::kStop)) {
    stopMotion(false);
  } else if (isCommand(number, Command::kEStop)) {
    stopMotion(true);
  } else {
    ++stats_.unknown_commands;  // CONFIG, SETV, gripper, IO requests...: not simulated
  }
}

void ArcosFirmware::stopMotion(bool brake) {
  velocity_mps_ = 0.0;
  move_remaining_m_.reset();
  heading_mode_ = Heading::kFree;
  rot_velocity_radps_ = 0.0;
  if (brake)
    sim_.halt();
  else
    sim_.setCommand({});
}

void ArcosFirmware::applyControl() {
  VelocityCommand command;
  const double max_speed = sim_.profile().limits.max_speed_mps;
  const double max_turn = sim_.profile().limits.max_turn_rate_radps;
  if (move_remaining_m_) {
    // A trapezoidal profile, as ARCOS runs a position move: at the SETV speed, braking at the
    // profile's deceleration to stop on the distance.
    const double cap = std::min(move_speed_mps_, max_speed);
    const double braking =
        std::sqrt(2.0 * sim_.profile().limits.max_accel_mps2 * std::abs(*move_remaining_m_));
    command.linear_mps = std::copysign(std::min(cap, braking), *move_remaining_m_);
  } else {
    command.linear_mps = velocity_mps_;
  }
  if (heading_mode_ == Heading::kRate) {
    command.angular_radps = rot_velocity_radps_;
  } else if (heading_mode_ == Heading::kTarget) {
    const double error = wrapAngle(heading_target_rad_ - reportedPose().theta);
    command.angular_radps = std::abs(error) < kHeadingDeadband_rad
                                ? 0.0
                                : std::clamp(kHeadingGain * error, -max_turn, max_turn);
  }
  if (!motors_enabled_ || (config_.strict && watchdog_tripped_))
    command = {};
  sim_.setCommand(command);
}

void ArcosFirmware::advance(double now_s) {
  const double dt = sim_.config().dt_s;
  while (sim_.time_s() + 0.5 * dt <= now_s) {
    if (state_ == ArcosServerState::kOpen && !watchdog_tripped_ &&
        sim_.time_s() - last_command_s_ > watchdog_s_)
      tripWatchdog();
    applyControl();
    sim_.step(sample_);
    if (move_remaining_m_) {
      const Pose2& odom = sim_.odometryPose();
      *move_remaining_m_ -= (odom.position() - move_last_pose_.position()).dot(odom.heading());
      move_last_pose_ = odom;
      if (std::abs(*move_remaining_m_) < kMoveDone_m)
        move_remaining_m_ = 0.0;  // hold position: 0 m left commands zero velocity
    }
    collectSonar(sample_);
    if (state_ == ArcosServerState::kOpen && sim_.time_s() + 1e-9 >= next_sip_s_) {
      sendSip();
      next_sip_s_ += sip_period_s_;
      if (next_sip_s_ < sim_.time_s())
        next_sip_s_ = sim_.time_s() + sip_period_s_;
    }
  }
  // The clock given may run ahead of the simulator (the watchdog uses the caller's time so that
  // it also trips while the caller skips steps).
  if (state_ == ArcosServerState::kOpen && !watchdog_tripped_ &&
      now_s - last_command_s_ > watchdog_s_)
    tripWatchdog();
}

void ArcosFirmware::tripWatchdog() {
  // ARCOS's communication watchdog: no command or PULSE for watchdog_s stops the robot.
  watchdog_tripped_ = true;
  ++stats_.watchdog_stops;
  if (config_.strict)
    sim_.halt();  // the set points stay: the next command resumes them (applyControl holds)
  else
    stopMotion(true);
}

void ArcosFirmware::collectSonar(const TelemetrySample& sample) {
  if (!sonar_enabled_)
    return;
  const auto& sonars = sim_.profile().sonars;
  for (const SonarReading& r : sample.sonar) {
    if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= sonar_cycle_m_.size())
      continue;
    const auto i = static_cast<std::size_t>(r.sensor);
    sonar_cycle_m_[i] = r.echo ? r.range_m : sonars[i].max_range_m;
  }
}

void ArcosFirmware::sendSip() {
  arcos::StandardSip sip;
  const VelocityCommand truth = sim_.trueVelocity();
  const bool moving = std::abs(truth.linear_mps) > 1e-4 || std::abs(truth.angular_radps) > 1e-4;
  sip.type = moving ? 0x33 : 0x32;
  const Pose2 pose = reportedPose();
  // 15-bit wrap-around of the position counters, as ARCOS sends them.
  const auto wrap15 = [](double units) {
    const auto n = static_cast<std::int64_t>(std::llround(units));
    return static_cast<std::uint16_t>(n & 0x7FFF);
  };
  sip.x_raw = wrap15(pose.x * 1000.0 / params_.dist_conv_mm);
  sip.y_raw = wrap15(pose.y * 1000.0 / params_.dist_conv_mm);
  sip.theta_raw = clampInt16(pose.theta / params_.angle_conv_rad);
  const VelocityCommand measured = sample_.measured_velocity;
  const double half_base = 0.5 * sim_.profile().drive.wheelbase_m;
  const double scale = 1000.0 / params_.vel_conv_mmps;
  sip.left_velocity =
      clampInt16((measured.linear_mps - measured.angular_radps * half_base) * scale);
  sip.right_velocity =
      clampInt16((measured.linear_mps + measured.angular_radps * half_base) * scale);
  sip.battery_decivolts = kBatteryDecivolts;
  std::uint16_t stall = 0;
  if (sample_.drive_stalled)
    stall |= 0x0101;  // both wheels: the body is blocked (the simulator's stall detection)
  const auto& bumpers = sim_.profile().bumpers;
  const std::uint32_t pressed = sim_.bumpers();
  int front = 0;
  int rear = 0;
  for (std::size_t i = 0; i < bumpers.size() && i < 32; ++i) {
    const bool is_front = std::cos(bumpers[i].normal_rad) >= 0.0;
    int& slot = is_front ? front : rear;
    if (slot >= 7)
      continue;
    if ((pressed >> i) & 1u)
      stall |= static_cast<std::uint16_t>(1u << ((is_front ? 9 : 1) + slot));
    ++slot;
  }
  sip.stall_and_bumpers = stall;
  if (heading_mode_ == Heading::kTarget)
    sip.control = clampInt16(heading_target_rad_ / params_.angle_conv_rad);
  std::uint16_t flags = motors_enabled_ ? 0x0001 : 0x0000;
  if (sonar_enabled_) {
    const std::size_t arrays = (sonar_cycle_m_.size() + 7) / 8;
    for (std::size_t a = 0; a < arrays && a < 4; ++a)
      flags |= static_cast<std::uint16_t>(1u << (1 + a));
  }
  sip.flags = flags;
  for (std::size_t i = 0; i < sonar_cycle_m_.size(); ++i) {
    if (!sonar_cycle_m_[i])
      continue;
    const double units = std::round(*sonar_cycle_m_[i] * 1000.0 / params_.range_conv_mm);
    sip.sonars.push_back({static_cast<std::uint8_t>(i),
                          static_cast<std::uint16_t>(std::clamp(units, 0.0, 65535.0))});
    sonar_cycle_m_[i].reset();
  }
  sip.io = std::array<std::uint8_t, 5>{};
  sip.battery_x10 = static_cast<std::uint16_t>(kBatteryDecivolts);
  sip.charge_state = 0;
  sip.rotational_velocity = clampInt16(radToDeg(measured.angular_radps) * 10.0);
  sip.fault_flags = 0;
  reply(arcos::encodeStandardSip(sip));
  ++stats_.sips;
}

std::vector<std::uint8_t> ArcosFirmware::takeOutput() {
  std::vector<std::uint8_t> out;
  out.swap(output_);
  return out;
}

}  // namespace irgs::app
