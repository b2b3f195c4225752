#pragma once
// The robot's defaults for the motion primitives (what a primitive's zero fields mean) and the
// shape of one control step's outcome. Firmware-grade: plain values.

#include <array>
#include <cstdint>
#include <optional>

#include "core/motion/primitive.hpp"
#include "core/motion/wall_follow.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::motion {

struct MotionSettings {
  double speed_mps = 0.2;                   // drive, segments, path following
  double turn_rate_radps = degToRad(60.0);  // on-the-spot turns
  double min_speed_mps = 0.02;              // floor near the end of a leg, so it arrives
  double min_turn_rate_radps = degToRad(4.0);
  double heading_tolerance_rad = degToRad(1.0);
  double arrival_tolerance_m = 0.01;
  // Forward-sonar stop of drive and segments when the spec gives 0: wall-follow distance plus
  // its front margin (where the wall follower itself would turn).
  double stop_clearance_m = 0.0;
  double no_progress_s = 5.0;  // watchdog: no progress this long ends a primitive (kNoProgress)
  double blocked_s = 1.0;      // in contact this long while turning or backing up: kBlocked
  double heading_gain = 2.5;   // 1/s, heading hold while driving
  double path_k2 = 4.0;        // path following (paper 004), 1/m^2 and 1/m
  double path_k3 = 3.0;
  WallFollowConfig follow;  // follow wall: side, distance and speed come from the spec

  double stopClearance() const {
    return stop_clearance_m > 0.0 ? stop_clearance_m : follow.distance_m + follow.front_margin_m;
  }
};

// A report a step asks for; the executor stamps it with the id, time and pose.
struct Note {
  ReportKind kind = ReportKind::kDone;
  Reason reason = Reason::kNone;
  std::int16_t index = -1;
};

struct StepOutcome {
  VelocityCommand command;
  // The heading the command steers toward, when the primitive has one (a turn's target, a
  // straight leg's hold heading, the wall follower's approach heading): a robot that holds a
  // heading itself (ARCOS HEAD) is given this instead of the turn rate.
  std::optional<double> heading_rad;
  // A straight drive toward a fixed end (a DRIVE's distance, a SEGMENTS leg): the distance left
  // along the heading (negative: backwards) and the speed to cover it at. A robot that drives a
  // distance itself (ARCOS MOVE) is given this instead of the speed, so a late link cannot carry
  // it past the end.
  struct Distance {
    double remaining_m = 0.0;
    double speed_mps = 0.0;
  };
  std::optional<Distance> distance;
  std::array<Note, 4> notes{};
  std::uint8_t note_count = 0;
  bool finished = false;

  void add(ReportKind kind, Reason reason = Reason::kNone, std::int16_t index = -1) {
    if (note_count < notes.size())
      notes[note_count++] = {kind, reason, index};
  }
  // Ends the primitive with this report; the wheels stop.
  void finish(ReportKind kind, Reason reason = Reason::kNone, std::int16_t index = -1) {
    add(kind, reason, index);
    finished = true;
    command = {};
    heading_rad.reset();
    distance.reset();
  }
};

// Watchdog on a measure that shrinks with progress (heading error, remaining distance): true
// once it has not improved by `step` for `timeout_s`.
class ProgressWatch {
 public:
  void restart(double time_s) {
    has_best_ = false;
    improved_at_s_ = time_s;
  }
  bool stalled(double measure, double step, double time_s, double timeout_s) {
    if (!has_best_ || measure < best_ - step) {
      best_ = measure;
      has_best_ = true;
      improved_at_s_ = time_s;
    }
    return time_s - improved_at_s_ > timeout_s;
  }

 private:
  double best_ = 0.0;
  bool has_best_ = false;
  double improved_at_s_ = 0.0;
};

// How long the body has been in contact; restart() when a new move starts.
class ContactWatch {
 public:
  void restart() { has_since_ = false; }
  // True once in contact for blocked_s without a break.
  bool blocked(bool in_contact, double time_s, double blocked_s) {
    if (!in_contact) {
      has_since_ = false;
      return false;
    }
    if (!has_since_) {
      since_s_ = time_s;
      has_since_ = true;
    }
    return time_s - since_s_ >= blocked_s;
  }

 private:
  double since_s_ = 0.0;
  bool has_since_ = false;
};

// Speed that still stops within `distance` at deceleration `accel` (with a margin for one
// step of latency), clamped to [min_speed, max_speed].
double approachSpeed(double distance, double accel, double min_speed, double max_speed);

}  // namespace irgs::motion
