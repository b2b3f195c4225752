#include "core/vision/ceiling_vision.hpp"

#include "core/vision/image_convert.hpp"

namespace irgs::vision {

CeilingObservation CeilingVisionResult::observation(double tilt_rad, double time_s) const {
  CeilingObservation o;
  o.time_s = time_s;
  o.tilt_rad = tilt_rad;
  o.markers = markers.markers;
  for (const auto& l : lights)
    o.lights.push_back(l.light);
  return o;
}

CeilingVision::CeilingVision(const VisionConfig& config)
    : config_(config),
      markers_(config.marker, config.top_view.px_per_m),
      lights_(config.light, config.top_view.px_per_m) {}

CeilingVisionResult CeilingVision::process(const cv::Mat& frame_rgb,
                                           const CeilingView& view) const {
  CeilingVisionResult r{TopViewGeometry(view, config_.top_view), {}, {}, {}};
  // (1) warp the frame to the top view; both pipelines work there.
  r.top_view = r.geometry.warp(frame_rgb);
  if (r.top_view.empty())
    return r;
  r.markers = markers_.detect(r.top_view, r.geometry);
  r.lights = lights_.detect(r.top_view, r.geometry);
  return r;
}

CeilingVisionResult CeilingVision::process(const RgbImage& frame, const CeilingView& view) const {
  return process(asRgbMat(frame), view);
}

}  // namespace irgs::vision
