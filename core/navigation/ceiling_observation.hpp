#pragma once
// What the ceiling camera reports to landmark navigation (002_…), and the one interface that
// produces it. Two producers exist: the vision pipelines on rendered or real frames
// (core/vision, irgs_vision: OpenCV) and, for tests of the navigation logic alone, an ideal
// geometric observer (core/navigation). The navigation state machine sees only this type.
//
// Frames: every position is the landmark's point on the ceiling plane projected vertically onto
// the floor, in the robot's body frame (x forward, y left, metres). Angles counter-clockwise.

#include <optional>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

// One detected ceiling marker (a 20 cm fluorescent-red square in 002_…). Markers look alike;
// their identity comes from the order along the planned route (002_… 3.6), not from the image.
struct MarkerDetection {
  Vec2 centre_body_m = Vec2::Zero();
  std::optional<double> heading_rad;  // the square's orientation mod 90 deg, when measured
  double score = 1.0;                 // template-match score in [0, 1]
};

// One detected ceiling light (a fluorescent tube or panel), its centre and long axis.
struct LightDetection {
  Vec2 centre_body_m = Vec2::Zero();
  double axis_rad = 0.0;  // direction of the long axis, mod pi
  double length_m = 0.0;  // extent along the axis as seen (may be cut by the image border)
};

// One camera frame's result.
struct CeilingObservation {
  double time_s = 0.0;
  double tilt_rad = 0.0;  // camera-to-ceiling angle theta of 002_… (35 deg far .. 90 deg up)
  std::vector<MarkerDetection> markers;
  std::vector<LightDetection> lights;
};

// Produces an observation for the camera at `tilt_rad` on a robot at `true_pose` (world frame).
// A simulated observer renders / projects the world there; a real camera ignores the pose.
class CeilingObserver {
 public:
  virtual ~CeilingObserver() = default;
  virtual CeilingObservation observe(const Pose2& true_pose, double tilt_rad, double time_s) = 0;
};

}  // namespace irgs
