#pragma once
// DRIVE: straight ahead (or back) a signed distance, holding the heading the robot had at the
// start, braking so it stops on the distance. Forward, it ends early with kFrontWall when the
// forward sonars see something within the clearance, and with kFailed(kBumped) on contact;
// backing up, contact for blocked_s ends it with kFailed(kBlocked) (a back-up starts in
// contact, so a touch alone is expected).

#include "core/motion/motion_input.hpp"
#include "core/motion/motion_settings.hpp"
#include "core/motion/sonar_memory.hpp"

namespace irgs::motion {

class DrivePrimitive {
 public:
  // False (nothing started) for a non-finite or zero distance, or a bad speed or clearance.
  bool start(const DriveSpec& spec, const MotionInput& now, const MotionSettings& settings,
             const MotionGeometry& geometry);
  // `sonar` holds the readings up to this step (the executor updates it).
  StepOutcome step(const MotionInput& input, const SonarMemory& sonar);
  double driven_m() const { return driven_m_; }

 private:
  const MotionSettings* settings_ = nullptr;
  const MotionGeometry* geometry_ = nullptr;
  DriveSpec spec_;
  Pose2 start_;
  double speed_mps_ = 0.0;
  double clearance_m_ = 0.0;
  double driven_m_ = 0.0;  // along the start heading, signed
  ProgressWatch watch_;
  ContactWatch contact_;
};

}  // namespace irgs::motion
