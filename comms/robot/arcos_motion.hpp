#pragma once
// Motion primitives for an ARCOS robot (Pioneer-class, docs/pioneer.md). ARCOS has no wall
// following or segment lists, but its own controllers hold a speed (VEL) and a heading (HEAD)
// between SIPs. So the ground station runs the primitive's logic — the same
// core/motion MotionExecutor the simulator and the MAVLink firmware run — on each SIP as it
// arrives and turns each step into set points for the robot's own loops:
//  - VEL: the step's forward speed;
//  - HEAD while the heading to reach is more than kHeadPhase_rad (1.5 deg) away: turns, corners,
//    legs and the wall follower's corrections: the Pioneer steers on its own controller and the
//    host only watches (behind 150-250 ms of link, 5 deg took 2.0x the in-process time, with
//    the host's late corrections, 1.5 deg 1.3x);
//  - RVEL within it (the last degree of a turn): one ARCOS degree is coarser than the 1-degree
//    turn tolerance, and a rate nudges instead;
//  - MOVE (after SETV, its speed) for a straight drive toward a fixed end — a DRIVE, a leg of
//    SEGMENTS: the robot stops on the distance by itself, so a late or stalled link cannot carry
//    it past the end (behind 400-600 ms and 0.5 s stalls, host-timed legs ran coverage into a
//    wall). One MOVE per leg; sent again for what is left when the robot stands still
//    kMoveRetry_s after it (a MOVE lost on the way, or one that stopped short).
// The ArcosCommandScheduler sends only changed values, at most 10 packets a second within the
// baud budget. Pure: no I/O, no threads; ArcosRobot steps it on its I/O thread (pure and unit
// tested here).

#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/motion/motion_executor.hpp"
#include "core/motion/primitive.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::comms {

struct ArcosMotionSetpoint {
  int vel_mmps = 0;
  // A straight drive the robot runs itself: a new MOVE (mm) at this SETV (mm/s) when set;
  // otherwise, while `moving`, the translational slot is left to the MOVE already sent.
  std::optional<int> move_mm;
  int move_speed_mmps = 0;
  bool moving = false;
  std::optional<int> head_deg;  // HEAD argument (ARCOS odometry frame, 0..359), else RVEL
  int rvel_degps = 0;
  friend bool operator==(const ArcosMotionSetpoint&, const ArcosMotionSetpoint&) = default;
};

// The HEAD argument for a heading in the ARCOS odometry frame: whole degrees in [0, 360).
int arcosHeadingArgument(double heading_rad);

class ArcosMotion {
 public:
  // Reports nobody takes are dropped oldest first beyond this many (storage stays bounded).
  static constexpr std::size_t kMaxKeptReports = 256;
  static constexpr double kHeadPhase_rad = degToRad(1.5);
  static constexpr double kMoveRetry_s = 2.0;

  explicit ArcosMotion(const RobotProfile& profile);

  // Every kind: the executor refuses what the robot's sonars cannot serve (kNoSensors).
  bool supports(motion::PrimitiveKind kind) const;
  // Starts on the newest SIP; refused with kNoAnswer before the first one.
  void start(const motion::Primitive& primitive);
  void cancel();
  // Ends a running primitive as failed (the link was lost: the set points were cleared).
  void abort(motion::Reason reason);

  // One SIP, in order. `map_to_arcos_rad` is the ARCOS odometry heading minus the map heading.
  // Returns the set point to want when a primitive ran this step, and the stop (zeros) on the
  // step it ended; nothing while idle, so teleop is left alone.
  std::optional<ArcosMotionSetpoint> onSample(const TelemetrySample& sample,
                                              double map_to_arcos_rad);
  // A stop owed to the robot by start()/cancel()/abort() (a primitive that ended between SIPs).
  bool takeStopOwed();

  bool running() const { return executor_.running(); }
  // Reports queued since the last call, oldest first (times are the SIPs' arrival times).
  std::vector<motion::MotionReport> takeReports();

 private:
  void collect();
  void keep(const motion::MotionReport& report);
  // The translational part of a step on a straight drive: a MOVE when this drive has none yet.
  void translate(const motion::StepOutcome::Distance& distance, ArcosMotionSetpoint& setpoint);

  // The MOVE the robot runs for the current straight drive: where it ends (odometry frame) and
  // when it was sent.
  struct MoveSent {
    Vec2 end = Vec2::Zero();
    double sent_s = 0.0;
  };

  motion::MotionExecutor executor_;
  MotionLimits limits_;
  std::optional<motion::MotionInput> last_input_;
  std::vector<motion::MotionReport> reports_;
  std::optional<MoveSent> move_;
  bool stop_owed_ = false;
};

}  // namespace irgs::comms
