#include "app/gui/camera_controller.hpp"

#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <cmath>

#include "app/gui/session_controller.hpp"
#include "core/camera/ceiling_scene.hpp"
#include "core/vision/image_convert.hpp"
#include "core/vision/vision_ceiling_observer.hpp"
#include "widgets/camera/camera_panel.hpp"

namespace irgs::gui {
namespace {

// The candidate's verdicts worth drawing as "looked at, rejected" (tiny specks are not).
bool drawRejected(vision::CandidateVerdict v) {
  return v == vision::CandidateVerdict::kNotFourSided ||
         v == vision::CandidateVerdict::kWrongSize || v == vision::CandidateVerdict::kPoorMatch;
}

// The panel's frame: images and every shape in both images' pixels.
widgets::CameraPanelFrame panelFrame(const vision::VisionCeilingObserver& observer, double time_s) {
  widgets::CameraPanelFrame f;
  f.frame = observer.lastFrame();
  f.source = "simulated";
  f.time_s = time_s;
  const CeilingView& view = *observer.lastView();
  f.tilt_deg = radToDeg(view.tiltRad());
  const vision::CeilingVisionResult& r = *observer.lastResult();
  if (!r.top_view.empty())
    f.top_view = vision::fromRgbMat(r.top_view);
  const vision::TopViewGeometry& g = r.geometry;
  // A top-view polygon drawn in the frame: through the body frame and the camera.
  auto inFrame = [&](const auto& top_points) {
    std::vector<Vec2> out;
    for (const Vec2& t : top_points)
      if (const auto px = view.project(g.pixelToBody(t)))
        out.push_back(*px);
    return out;
  };
  auto inTop = [](const auto& top_points) {
    return std::vector<Vec2>(top_points.begin(), top_points.end());
  };
  for (const auto& c : r.markers.candidates) {
    if (c.verdict == vision::CandidateVerdict::kAccepted) {
      f.frame_overlay.markers.push_back(inFrame(c.corners_top_px));
      f.top_overlay.markers.push_back(inTop(c.corners_top_px));
    } else if (drawRejected(c.verdict)) {
      f.frame_overlay.rejected.push_back(inFrame(c.corners_top_px));
      f.top_overlay.rejected.push_back(inTop(c.corners_top_px));
    }
  }
  for (const auto& l : r.lights) {
    f.frame_overlay.lights.push_back(inFrame(l.box_top_px));
    f.top_overlay.lights.push_back(inTop(l.box_top_px));
  }
  // The target, as 002_…'s state machine picks it: the nearest marker, else the farthest light.
  std::optional<Vec2> target_body;
  if (!r.markers.markers.empty())
    target_body = r.markers.markers.front().centre_body_m;
  else if (!r.lights.empty())
    target_body = r.lights.front().light.centre_body_m;
  if (target_body) {
    f.top_overlay.target = g.bodyToPixel(*target_body);
    f.frame_overlay.target = view.project(*target_body);
  }
  const Vec2 robot_top = g.bodyToPixel(Vec2(view.mount().x_m, view.mount().y_m));
  if (robot_top.x() >= 0 && robot_top.y() >= 0 && robot_top.x() < g.width() &&
      robot_top.y() < g.height())
    f.top_overlay.robot = robot_top;
  f.markers = static_cast<int>(r.markers.markers.size());
  f.lights = static_cast<int>(r.lights.size());
  return f;
}

}  // namespace

CameraController::CameraController(SessionController& session, QMainWindow& window)
    : QObject(&window), session_(session) {
  dock_ = new QDockWidget(tr("Camera"), &window);
  dock_->setObjectName(QStringLiteral("cameraDock"));
  panel_ = new widgets::CameraPanel(dock_);
  dock_->setWidget(panel_);
  window.addDockWidget(Qt::BottomDockWidgetArea, dock_);
  dock_->hide();
  QAction* toggle = dock_->toggleViewAction();
  toggle->setText(tr("&Camera Panel"));
  toggle->setToolTip(tr("What the ceiling camera sees, its top view and the detected landmarks"));
  if (auto* view_menu = window.findChild<QMenu*>(QStringLiteral("viewMenu"))) {
    view_menu->addSeparator();
    view_menu->addAction(toggle);
  }

  connect(&session_, &SessionController::worldLoaded, this, &CameraController::rebuild);
  connect(&session_, &SessionController::worldEdited, this, &CameraController::rebuild);
  connect(&session_, &SessionController::robotReplaced, this, [this] {
    last_frame_time_s_.reset();
    rebuild();
  });
  connect(&session_, &SessionController::robotStateChanged, this, &CameraController::onSample);
  connect(panel_, &widgets::CameraPanel::tiltModeChanged, this, [this](bool, double) {
    last_frame_time_s_.reset();  // show the new tilt with the next sample
  });
  connect(dock_, &QDockWidget::visibilityChanged, this, [this](bool visible) {
    if (visible && session_.latestSample() && session_.latestSample()->true_pose)
      showFrameAt(*session_.latestSample()->true_pose, session_.latestSample()->time_s);
  });
  rebuild();
}

CameraController::~CameraController() = default;

void CameraController::rebuild() {
  const auto cam = ceilingCameraFromProfile(session_.profile());
  camera_ = cam.config;
  if (!cam.errors.empty())
    session_.report(EventLevel::kWarning,
                    tr("Robot profile ceiling_camera: %1 (using the default camera)")
                        .arg(QString::fromStdString(cam.errors.front())));
  const WorldMap& map = session_.worldMap();
  const double ceiling = camera_.ceilingHeight(map.ceiling_height_m);
  if (!(ceiling - camera_.mount.z_m > 0.0)) {
    observer_.reset();
    panel_->showMessage(tr("The ceiling (%1 m) is not above the camera").arg(ceiling));
    return;
  }
  RenderSettings render;
  render.supersample = 1;  // the GUI renders on its own thread: a quarter of the rays
  observer_ = std::make_unique<vision::VisionCeilingObserver>(sceneFromMap(map), camera_,
                                                              vision::VisionConfig{}, render);
  if (map.markers.empty() && map.lights.empty())
    panel_->showMessage(tr("This map has no ceiling markers or lights"));
}

double CameraController::autoTiltRad(const Pose2& pose) const {
  const Vec2 camera_world = pose.toWorld(Vec2(camera_.mount.x_m, camera_.mount.y_m));
  std::optional<double> nearest;
  for (const CeilingMarker& m : session_.worldMap().markers) {
    const Vec2 body = pose.toBody(m.position);
    if (body.x() < camera_.mount.x_m - 0.3)  // behind the camera: it cannot tilt backwards
      continue;
    const double d = (m.position - camera_world).norm();
    if (!nearest || d < *nearest)
      nearest = d;
  }
  return camera_.tilt.tiltFor(nearest.value_or(camera_.tilt.far_m));
}

bool CameraController::showFrameAt(const Pose2& pose, double time_s) {
  if (!observer_)
    return false;
  const double tilt = panel_->autoTilt() ? autoTiltRad(pose) : degToRad(panel_->fixedTiltDeg());
  observer_->observe(pose, tilt, time_s);
  panel_->showFrame(panelFrame(*observer_, time_s));
  last_frame_time_s_ = time_s;
  wall_since_frame_.start();
  ++frames_shown_;
  return true;
}

void CameraController::onSample(const TelemetrySample& sample) {
  if (!dock_->isVisible())
    return;
  if (!sample.true_pose) {
    if (!last_frame_time_s_)
      panel_->showMessage(tr("No simulated camera: this robot reports no ground truth"));
    return;
  }
  if (last_frame_time_s_ && sample.time_s >= *last_frame_time_s_ &&
      (sample.time_s - *last_frame_time_s_ < kFramePeriodS ||
       (wall_since_frame_.isValid() && wall_since_frame_.elapsed() < min_wall_period_ms_)))
    return;
  showFrameAt(*sample.true_pose, sample.time_s);
}

}  // namespace irgs::gui
