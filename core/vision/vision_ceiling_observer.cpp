#include "core/vision/vision_ceiling_observer.hpp"

namespace irgs::vision {

VisionCeilingObserver::VisionCeilingObserver(CeilingScene scene, CeilingCameraConfig camera,
                                             VisionConfig vision, RenderSettings render)
    : scene_(std::move(scene)), camera_(camera), vision_(vision), render_(render) {}

CeilingObservation VisionCeilingObserver::observe(const Pose2& true_pose, double tilt_rad,
                                                  double time_s) {
  const CeilingView view(camera_.intrinsics, camera_.mount,
                         camera_.ceilingHeight(scene_.ceiling_height_m), tilt_rad);
  RenderSettings settings = render_;
  settings.seed = render_.seed + frames_;
  ++frames_;
  last_frame_ = renderCeiling(view, scene_, true_pose, settings);
  last_view_ = view;
  last_result_ = vision_.process(last_frame_, view);
  return last_result_->observation(tilt_rad, time_s);
}

}  // namespace irgs::vision
