#pragma once
// The ceiling camera in the GUI (issue 7, item 5): owns a VisionCeilingObserver for the loaded
// map and the robot profile's ceiling camera, renders a frame from the simulated robot's true
// pose a few times per second while the "Camera" dock is visible, runs the vision pipelines on it
// and shows the frame, the top view and the detections in the CameraPanel. The tilt follows the
// profile's tilt law (002_…, A002-5: from the distance of the nearest marker ahead) or is fixed
// from the panel.
//
// Needs ground truth (simulator mode): a linked robot's samples carry none; the panel then says
// so (a live camera would be read through irgs_vision_io, see irgs-vision-eval --device).

#include <QElapsedTimer>
#include <QObject>
#include <memory>
#include <optional>

#include "core/camera/ceiling_camera_config.hpp"
#include "core/robot/telemetry.hpp"

class QDockWidget;
class QMainWindow;

namespace irgs::vision {
class VisionCeilingObserver;
}

namespace irgs::widgets {
class CameraPanel;
}

namespace irgs::gui {

class SessionController;

class CameraController : public QObject {
  Q_OBJECT

 public:
  static constexpr double kFramePeriodS = 0.25;  // simulated time between frames (4 Hz)
  // Wall-clock floor between frames by default: at fast simulation speeds the GUI thread still
  // renders at most 5 frames per second.
  static constexpr int kDefaultMinWallPeriodMs = 200;

  // Adds the "Camera" dock (hidden until shown from the View menu) to `window`, and its toggle
  // to the window's View menu when there is one (objectName "viewMenu").
  CameraController(SessionController& session, QMainWindow& window);
  ~CameraController() override;

  QDockWidget& dock() const { return *dock_; }
  widgets::CameraPanel& panel() const { return *panel_; }
  const CeilingCameraConfig& camera() const { return camera_; }

  // Renders, processes and shows the frame of a robot at `pose` now, at the tilt the panel asks
  // for (automatic: the tilt law). Returns false when there is nothing to render.
  bool showFrameAt(const Pose2& pose, double time_s);
  // The automatic tilt at `pose`: the tilt law applied to the nearest marker ahead of the
  // camera (the farthest tilt when none is within reach).
  double autoTiltRad(const Pose2& pose) const;
  int framesShown() const { return frames_shown_; }
  void setMinWallPeriodMs(int ms) { min_wall_period_ms_ = ms; }

 private:
  void rebuild();
  void onSample(const TelemetrySample& sample);

  SessionController& session_;
  QDockWidget* dock_ = nullptr;
  widgets::CameraPanel* panel_ = nullptr;
  CeilingCameraConfig camera_;
  std::unique_ptr<vision::VisionCeilingObserver> observer_;
  std::optional<double> last_frame_time_s_;
  QElapsedTimer wall_since_frame_;
  int min_wall_period_ms_ = kDefaultMinWallPeriodMs;
  int frames_shown_ = 0;
};

}  // namespace irgs::gui
