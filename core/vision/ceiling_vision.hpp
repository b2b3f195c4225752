#pragma once
// One frame through the ceiling-landmark pipelines: top view, markers, lights. The same code
// runs on rendered frames (VisionCeilingObserver) and on real ones (app/tools/irgs-vision-eval
// --image/--video/--device).

#include <opencv2/core.hpp>

#include "core/camera/camera_model.hpp"
#include "core/camera/image.hpp"
#include "core/navigation/ceiling_observation.hpp"
#include "core/vision/light_detector.hpp"
#include "core/vision/marker_detector.hpp"
#include "core/vision/top_view.hpp"
#include "core/vision/vision_config.hpp"

namespace irgs::vision {

struct CeilingVisionResult {
  TopViewGeometry geometry;
  cv::Mat top_view;  // CV_8UC3, R, G, B
  MarkerDetectionResult markers;
  std::vector<LabelledLight> lights;  // farthest ahead first

  // The observation navigation consumes.
  CeilingObservation observation(double tilt_rad, double time_s) const;
};

class CeilingVision {
 public:
  explicit CeilingVision(const VisionConfig& config = {});

  const VisionConfig& config() const { return config_; }
  // `frame` is R, G, B as seen through `view` (its tilt is the camera's at exposure time).
  CeilingVisionResult process(const cv::Mat& frame_rgb, const CeilingView& view) const;
  CeilingVisionResult process(const RgbImage& frame, const CeilingView& view) const;

 private:
  VisionConfig config_;
  MarkerDetector markers_;
  LightDetector lights_;
};

}  // namespace irgs::vision
