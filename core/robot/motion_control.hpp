#pragma once
// Optional capability of an irgs::Robot: it runs motion primitives (core/motion/primitive.hpp)
// itself, next to its wheels. The in-process simulator runs them on every simulator step; a
// MAVLink robot runs them in its firmware (dialect commands, docs/protocol.md); an ARCOS robot
// runs what it can (MOVE, HEAD/DHEAD) with the ground station supervising the rest at the SIP
// rate. The host sends a primitive and reacts to the reports; it never closes these loops over
// the link itself.

#include <vector>

#include "core/motion/primitive.hpp"

namespace irgs {

class MotionControl {
 public:
  virtual ~MotionControl() = default;
  // True when this robot can run primitives of this kind.
  virtual bool supports(motion::PrimitiveKind kind) const = 0;
  // Starts `primitive`, replacing (cancelling) the one running. The outcome arrives as reports:
  // kStarted or kRefused first, then progress, then one final report. Over a link the start
  // travels with the link's delay; the robot keeps its previous state until it arrives.
  virtual void start(const motion::Primitive& primitive) = 0;
  // Ends the running primitive (kCancelled) and stops the wheels.
  virtual void cancel() = 0;
  // The reports received since the last call, oldest first, on the robot's clock as the
  // samples of Robot::update (a report is taken only after the samples up to its time).
  virtual std::vector<motion::MotionReport> takeReports() = 0;
};

}  // namespace irgs
