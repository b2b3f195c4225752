#pragma once
// The acceptance measurements of the ceiling camera and vision (issue 7), shared by the
// irgs-vision-eval tool (full tables, docs/landmark-navigation.md) and the tests (smaller sets,
// asserted thresholds). Every scene, pose and noise draw comes from the seed.

#include <array>
#include <cstdint>
#include <vector>

#include "core/camera/ceiling_camera_config.hpp"
#include "core/camera/ceiling_renderer.hpp"
#include "core/vision/vision_config.hpp"

namespace irgs::vision {

struct ErrorStats {
  int count = 0;     // points or detections measured
  int expected = 0;  // points or markers that should have been measured
  double mean_m = 0.0;
  double rms_m = 0.0;
  double max_m = 0.0;
};

// (a) A grid of small dark squares on the ceiling, rendered at `tilt_rad`, warped to the top view
// and located there (dark blobs, centroids): the metric error of the top view at each grid point
// within the working range. `tilt_error_rad` warps with a tilt that is off by that much (a servo
// or calibration error) to show how sensitive the metric scale is.
struct TopViewErrorRow {
  double tilt_rad = 0.0;
  ErrorStats exact;     // warped with the true tilt
  ErrorStats tilt_off;  // warped with tilt + tilt_error_rad
};
TopViewErrorRow topViewGridError(const CeilingCameraConfig& camera, const VisionConfig& vision,
                                 double tilt_rad, double tilt_error_rad, std::uint64_t seed);

// (a) The marker detector's centre error at `tilt_rad`: `frames` frames, each with one marker at
// a random place in the view within the working range.
ErrorStats markerCentreError(const CeilingCameraConfig& camera, const VisionConfig& vision,
                             double tilt_rad, int frames, std::uint64_t seed);

// (b) Detection on generated frames: random tilt (35..90 deg), pose, exposure, blur and noise,
// 1-3 markers, 1-3 lights (tubes and panels) and 0-2 distractors (red signs, coloured squares,
// oversized red squares) per frame.
struct DetectionStats {
  int frames = 0;
  int markers_in_range = 0;  // fully in the image, within the camera's working range
  int markers_in_range_found = 0;
  int detections = 0;
  int detections_true = 0;   // within half a marker of a real marker
  ErrorStats marker_centre;  // of the found in-range markers
  // Recall by horizontal distance from the camera, 1 m bands 0-1 .. 5-6 m (markers are placed
  // up to the top view's range, beyond the working range too).
  std::array<int, 6> band_markers{};
  std::array<int, 6> band_found{};
  int lights_visible = 0;  // fully inside the image and the top view
  int lights_found = 0;
  ErrorStats light_centre;
  double recall() const {
    return markers_in_range ? static_cast<double>(markers_in_range_found) / markers_in_range : 1.0;
  }
  double precision() const {
    return detections ? static_cast<double>(detections_true) / detections : 1.0;
  }
};
DetectionStats evaluateDetection(const CeilingCameraConfig& camera, const VisionConfig& vision,
                                 int frames, std::uint64_t seed);

}  // namespace irgs::vision
