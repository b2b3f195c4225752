#pragma once
// A geometric stand-in for the ceiling camera and its detectors, for testing the navigation
// logic without rendering or OpenCV: it projects the map's markers and lights into the field of
// view of a pinhole camera tilted by theta (camera_tilt.hpp) and reports what falls inside,
// with seeded Gaussian noise on the positions. The real pipelines (irgs_vision) produce the same
// CeilingObservation from images.
//
// Camera frame: the camera sits `mount_x_m` ahead of the body origin, `camera_height_m` above
// the floor, looking along the body's forward axis raised by theta above the horizontal plane
// (theta = 90 deg: straight up). A ceiling point is seen when its direction lies within half
// the horizontal and vertical fields of view of the optical axis and within the working range.

#include <cstdint>

#include "core/navigation/ceiling_observation.hpp"
#include "core/sim/random.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct IdealCameraParams {
  double camera_height_m = 0.6;
  double mount_x_m = 0.0;
  double horizontal_fov_rad = 1.0471975511965976;  // 60 deg (640 px)
  double vertical_fov_rad = 0.8028514559173916;    // 46 deg (480 px)
  double marker_range_m = 6.0;  // slant range up to which a 20 cm marker is detected
  double light_range_m = 10.0;
  double position_stddev_m = 0.005;      // at zero range
  double position_stddev_per_m = 0.005;  // grows with the slant range
  double detection_probability = 1.0;    // each landmark, each frame
};

class IdealCeilingObserver final : public CeilingObserver {
 public:
  IdealCeilingObserver(const WorldMap& map, IdealCameraParams params, std::uint64_t seed);
  CeilingObservation observe(const Pose2& true_pose, double tilt_rad, double time_s) override;

  // True when the ceiling point (world frame) is in view of the camera on `pose` at `tilt_rad`;
  // `slant_m` gets the distance from the camera.
  bool inView(const Pose2& pose, double tilt_rad, const Vec2& ceiling_point, double& slant_m) const;

 private:
  std::vector<CeilingMarker> markers_;
  std::vector<CeilingLight> lights_;
  double ceiling_height_m_;
  IdealCameraParams params_;
  SimRandom rng_;
};

}  // namespace irgs
