#pragma once
// A CeilingObserver that does real image processing in simulation: it renders the camera's
// frame of the ceiling (core/camera) at the robot's true pose and tilt, then runs the OpenCV
// pipelines (CeilingVision) on it. Navigation using it sees exactly what it would see from a
// real camera running the same code, detection misses and errors included.

#include <cstdint>

#include "core/camera/ceiling_camera_config.hpp"
#include "core/camera/ceiling_renderer.hpp"
#include "core/camera/ceiling_scene.hpp"
#include "core/navigation/ceiling_observation.hpp"
#include "core/vision/ceiling_vision.hpp"

namespace irgs::vision {

class VisionCeilingObserver final : public CeilingObserver {
 public:
  // Frame k (k = 0, 1, ...) is rendered with noise seed `render.seed + k`: a run is repeatable.
  VisionCeilingObserver(CeilingScene scene, CeilingCameraConfig camera, VisionConfig vision = {},
                        RenderSettings render = {});

  CeilingObservation observe(const Pose2& true_pose, double tilt_rad, double time_s) override;

  // The last frame, for display (empty before the first observe()).
  const RgbImage& lastFrame() const { return last_frame_; }
  // The last pipeline result (top view, candidates, lights), nothing before the first frame.
  const std::optional<CeilingVisionResult>& lastResult() const { return last_result_; }
  // The camera view of the last frame.
  const std::optional<CeilingView>& lastView() const { return last_view_; }

  const CeilingScene& scene() const { return scene_; }
  void setScene(CeilingScene scene) { scene_ = std::move(scene); }
  const CeilingCameraConfig& camera() const { return camera_; }
  RenderSettings& renderSettings() { return render_; }
  std::uint64_t framesRendered() const { return frames_; }

 private:
  CeilingScene scene_;
  CeilingCameraConfig camera_;
  CeilingVision vision_;
  RenderSettings render_;
  std::uint64_t frames_ = 0;
  RgbImage last_frame_;
  std::optional<CeilingVisionResult> last_result_;
  std::optional<CeilingView> last_view_;
};

}  // namespace irgs::vision
