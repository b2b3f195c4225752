#include "app/gui/localization_controller.hpp"

#include <QAction>
#include <QActionGroup>
#include <QComboBox>
#include <QDockWidget>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMouseEvent>
#include <QPushButton>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "app/gui/event_format.hpp"
#include "app/gui/session_controller.hpp"
#include "core/calibration/profile_calibration.hpp"
#include "core/estimation/stereo_measurement_model.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/plots/error_plot_panel.hpp"

namespace irgs::gui {
namespace {

// A pose the user drags out starts with this uncertainty (they place it by eye).
constexpr double kDraggedPositionStddev_m = 0.3;
constexpr double kDraggedHeadingStddev_rad = 10.0 * kPi / 180.0;
constexpr double kMinDrag_px = 6.0;  // shorter: keep the previous heading

const QColor kEstimateColour(31, 119, 180);
const QColor kDeadReckoningColour(230, 120, 0);
const QColor kTruthColour(30, 150, 60);

const char* sensorName(std::size_t index) {
  static const char* names[] = {"right", "left", "front"};
  return index < 3 ? names[index] : "sensor";
}

const char* echoName(EchoStatus status) {
  switch (status) {
    case EchoStatus::kEcho:
      return "echo";
    case EchoStatus::kNoReflector:
      return "nothing in range";
    case EchoStatus::kDropout:
      return "dropout";
    case EchoStatus::kBeyondMaxTof:
      return "beyond max TOF";
  }
  return "?";
}

QString gateText(double gate) {
  return std::isfinite(gate) ? QString::number(gate, 'f', 2) : QStringLiteral("inf");
}

}  // namespace

LocalizationController::LocalizationController(SessionController& session,
                                               widgets::MapCanvas& canvas, QMainWindow& window,
                                               QAction* before_menu)
    : QObject(&window), session_(session), canvas_(canvas), window_(window) {
  // ---- dock: controls + plots ----
  dock_ = new QDockWidget(tr("Localization"), &window);
  dock_->setObjectName(QStringLiteral("localizationDock"));
  auto* body = new QWidget(dock_);
  auto* layout = new QVBoxLayout(body);
  layout->setContentsMargins(4, 2, 4, 2);
  auto* controls = new QHBoxLayout;
  choice_ = new QComboBox(body);
  choice_->setObjectName(QStringLiteral("estimatorChoice"));
  choice_->addItem(tr("Off"));
  for (EstimatorKind k : kAllEstimatorKinds)
    choice_->addItem(tr(displayName(k)), static_cast<int>(k));
  drag_button_ = new QPushButton(tr("Set Initial Pose…"), body);
  drag_button_->setCheckable(true);
  drag_button_->setToolTip(
      tr("Press on the map at the estimator's initial position and drag towards its heading"));
  auto* pause = new QPushButton(tr("Pause"), body);
  auto* step = new QPushButton(tr("Step Update"), body);
  step->setToolTip(
      tr("Pause and advance to the next estimator update; the console shows the "
         "innovation, gate value and matched feature"));
  auto* restart_button = new QPushButton(tr("Restart"), body);
  state_ = new QLabel(body);
  controls->addWidget(new QLabel(tr("Estimator:"), body));
  controls->addWidget(choice_);
  controls->addWidget(drag_button_);
  controls->addWidget(pause);
  controls->addWidget(step);
  controls->addWidget(restart_button);
  controls->addWidget(state_, 1);
  layout->addLayout(controls);
  plots_ = new widgets::ErrorPlotPanel(body);
  layout->addWidget(plots_, 1);
  dock_->setWidget(body);
  window.addDockWidget(Qt::BottomDockWidgetArea, dock_);
  dock_->hide();

  // ---- menu ----
  menu_ = new QMenu(tr("&Localization"), &window);
  kind_group_ = new QActionGroup(this);
  QAction* off = menu_->addAction(tr("&Off"));
  off->setCheckable(true);
  off->setChecked(true);
  kind_group_->addAction(off);
  connect(off, &QAction::triggered, this, [this] { setEstimator(std::nullopt); });
  for (EstimatorKind k : kAllEstimatorKinds) {
    QAction* a = menu_->addAction(tr(displayName(k)));
    a->setCheckable(true);
    a->setData(static_cast<int>(k));
    kind_group_->addAction(a);
    connect(a, &QAction::triggered, this, [this, k] { setEstimator(k); });
  }
  menu_->addSeparator();
  drag_action_ = menu_->addAction(tr("Set &Initial Pose by Dragging"));
  drag_action_->setCheckable(true);
  connect(drag_action_, &QAction::toggled, this, &LocalizationController::armInitialPoseDrag);
  QAction* step_action =
      menu_->addAction(tr("Step &Update"), this, &LocalizationController::stepUpdate);
  step_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_U));
  menu_->addAction(tr("&Restart Estimator"), this, [this] { restart(); });
  menu_->addSeparator();
  menu_->addAction(dock_->toggleViewAction());
  if (before_menu != nullptr)
    window.menuBar()->insertMenu(before_menu, menu_);
  else
    window.menuBar()->addMenu(menu_);

  connect(choice_, &QComboBox::activated, this, [this](int index) {
    if (index <= 0)
      setEstimator(std::nullopt);
    else
      setEstimator(static_cast<EstimatorKind>(choice_->itemData(index).toInt()));
  });
  connect(drag_button_, &QPushButton::toggled, this, &LocalizationController::armInitialPoseDrag);
  connect(pause, &QPushButton::clicked, this, [this] { session_.setPaused(!session_.paused()); });
  connect(&session_, &SessionController::pausedChanged, pause,
          [pause](bool paused) { pause->setText(paused ? tr("Run") : tr("Pause")); });
  connect(step, &QPushButton::clicked, this, &LocalizationController::stepUpdate);
  connect(restart_button, &QPushButton::clicked, this, [this] { restart(); });

  // Every sample feeds the estimator; the canvas overlay follows the display rate.
  connect(&session_, &SessionController::sampleIntegrated, this, &LocalizationController::onSample);
  connect(&session_, &SessionController::robotStateChanged, this,
          &LocalizationController::updateOverlay);
  connect(&session_, &SessionController::robotReplaced, this, [this] { restart(); });
  connect(&session_, &SessionController::worldLoaded, this, [this] {
    initial_pose_.reset();  // a new map: its own start pose
    restart();
  });
  canvas_alive_ = &canvas_;
  canvas_.installEventFilter(this);
  syncUi();
}

// The canvas may already be gone (a sibling child of the window deleted first); Qt removes the
// event filter itself when this object is destroyed.
LocalizationController::~LocalizationController() = default;

std::optional<EstimatorKind> LocalizationController::estimator() const {
  return kind_;
}

void LocalizationController::setEstimator(std::optional<EstimatorKind> kind) {
  kind_ = kind;
  if (kind_)
    dock_->show();
  restart();
  if (kind_)
    session_.report(EventLevel::kInfo,
                    tr("Localization: %1 from %2")
                        .arg(tr(displayName(*kind_)),
                             formatPose(initial_pose_.value_or(session_.worldMap().start))));
  else
    session_.report(EventLevel::kInfo, tr("Localization off"));
}

void LocalizationController::setInitialPose(const Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta))
    return;
  initial_pose_ = Pose2{pose.x, pose.y, wrapAngle(pose.theta)};
  session_.report(EventLevel::kInfo, tr("Localization: initial pose %1 (1σ %2 m, %3°)")
                                         .arg(formatPose(*initial_pose_))
                                         .arg(kDraggedPositionStddev_m)
                                         .arg(radToDeg(kDraggedHeadingStddev_rad), 0, 'f', 0));
  restart();
}

void LocalizationController::restart() {
  runner_.reset();
  last_with_readings_ = {};
  warned_no_truth_ = false;
  warned_no_gyro_ = false;
  warned_no_mouse_ = false;
  warned_no_casters_ = false;
  plots_->clear();
  if (kind_) {
    EstimatorRunnerConfig config;
    config.kind = *kind_;
    if (initial_pose_) {
      config.initial_position_stddev_m = kDraggedPositionStddev_m;
      config.initial_heading_stddev_rad = kDraggedHeadingStddev_rad;
      // A belief placed by eye can be far off: gate the outliers instead of trusting them.
      config.ekf.gate = 16.0;
    }
    // The gyro's scale factor and temperature bias as calibrated for this robot (the gyro
    // wizard writes them into the profile); without them the filter integrates the raw rate
    // and its bias state has to absorb the error.
    config.gyro_calibration = profileGyroCalibration(session_.profile());
    if (adjust_)
      adjust_(config);
    if (*kind_ == EstimatorKind::kEncoderGyro && !config.gyro_calibration)
      session_.report(EventLevel::kInfo,
                      tr("Localization: the robot profile has no gyro calibration — the raw gyro "
                         "rate is used (calibrate the gyro to record one)"));
    const Pose2 start = initial_pose_.value_or(session_.worldMap().start);
    try {
      runner_ =
          std::make_unique<EstimatorRunner>(session_.worldMap(), session_.profile(), start, config);
    } catch (const std::invalid_argument& e) {
      session_.report(EventLevel::kError,
                      tr("Localization cannot start: %1").arg(QString::fromUtf8(e.what())));
      kind_.reset();
    }
    plots_->setEstimatorName(kind_ ? tr("%1 — error against truth").arg(tr(displayName(*kind_)))
                                   : tr("No estimator running"));
  } else {
    plots_->setEstimatorName(tr("No estimator running"));
  }
  syncUi();
  updateOverlay();
}

void LocalizationController::syncUi() {
  const int index = kind_ ? choice_->findData(static_cast<int>(*kind_)) : 0;
  choice_->setCurrentIndex(std::max(index, 0));
  for (QAction* a : kind_group_->actions())
    a->setChecked(kind_ ? (a->data().isValid() && a->data().toInt() == static_cast<int>(*kind_))
                        : !a->data().isValid());
  state_->setText(
      kind_ ? (initial_pose_ ? tr("initial pose set by hand") : tr("initial pose: map start"))
            : QString());
}

void LocalizationController::setConfigAdjuster(ConfigAdjuster adjust) {
  adjust_ = std::move(adjust);
  if (kind_)
    restart();
}

void LocalizationController::onSample(const TelemetrySample& sample) {
  if (!runner_)
    return;
  if (!sample.true_pose && !warned_no_truth_) {
    warned_no_truth_ = true;
    session_.report(EventLevel::kWarning,
                    tr("Localization: this robot reports no ground truth — no simulated echoes "
                       "and no error plots (dead reckoning only)"));
  }
  if (!sample.gyro && *kind_ == EstimatorKind::kEncoderGyro && !warned_no_gyro_) {
    warned_no_gyro_ = true;
    session_.report(EventLevel::kWarning,
                    tr("Localization: this robot has no gyro — the encoder + gyro filter runs "
                       "on the encoders alone (irgs-sim --localize encoder-gyro simulates one)"));
  }
  if (!sample.casters && *kind_ == EstimatorKind::kStereoEkfCaster && !warned_no_casters_) {
    warned_no_casters_ = true;
    session_.report(EventLevel::kWarning,
                    tr("Localization: this robot reports no caster encoders — the three-caster "
                       "EKF holds its estimate between sonar updates"));
  }
  if (!sample.mouse && *kind_ == EstimatorKind::kMouseOdometry && !warned_no_mouse_) {
    warned_no_mouse_ = true;
    session_.report(EventLevel::kWarning,
                    tr("Localization: this robot reports no floor-sensor counts — the mouse "
                       "odometry holds its estimate"));
  }
  const EstimatorStep& step = runner_->feed(sample);
  if (!step.readings.empty())
    last_with_readings_ = step;
  if (step.error) {
    widgets::ErrorPlotPoint point;
    point.time_s = session_.displayTime_s();
    point.error_x_m = (*step.error)(kLocX);
    point.error_y_m = (*step.error)(kLocY);
    point.error_theta_rad = (*step.error)(kLocPhi);
    const LocCov& p = step.covariance;
    point.sigma_x_m = std::sqrt(std::max(p(0, 0), 0.0));
    point.sigma_y_m = std::sqrt(std::max(p(1, 1), 0.0));
    point.sigma_theta_rad = std::sqrt(std::max(p(2, 2), 0.0));
    const double denom = point.sigma_x_m * point.sigma_y_m;
    point.correlation_xy = denom > 0.0 ? std::clamp(p(0, 1) / denom, -1.0, 1.0) : 0.0;
    point.dr_position_error_m = (step.dead_reckoning.position() - step.truth->position()).norm();
    point.nees = step.nees.value_or(-1.0);
    plots_->addPoint(point);
  }
  if (stepping_ && !step.readings.empty())
    printStep(step);
}

void LocalizationController::updateOverlay() {
  if (canvas_alive_.isNull())
    return;
  widgets::EstimatorOverlay overlay;
  if (runner_) {
    const EstimatorStep& step = runner_->lastStep();
    if (step.truth)
      overlay.poses.push_back({tr("true"), kTruthColour, *step.truth, std::nullopt});
    if (*kind_ != EstimatorKind::kDeadReckoning)
      overlay.poses.push_back({tr("DR"), kDeadReckoningColour, step.dead_reckoning, std::nullopt});
    const QString label = *kind_ == EstimatorKind::kStereoEkf         ? tr("EKF")
                          : *kind_ == EstimatorKind::kStereoEkfCaster ? tr("EKF (J+)")
                          : *kind_ == EstimatorKind::kEncoderGyro     ? tr("enc+gyro")
                          : *kind_ == EstimatorKind::kMouseOdometry   ? tr("mouse")
                                                                      : tr("DR");
    overlay.poses.push_back(
        {label, *kind_ == EstimatorKind::kDeadReckoning ? kDeadReckoningColour : kEstimateColour,
         step.estimate, Eigen::Matrix3d(step.covariance)});
    const LocalizationMap& map = runner_->localizationMap();
    const auto& sensors = runner_->config().sensors;
    for (const StereoReadingRecord& r : last_with_readings_.readings) {
      if (r.update.match == MatchKind::kNone || !last_with_readings_.truth)
        continue;
      widgets::MatchedFeatureMarker m;
      m.accepted = r.accepted;
      if (r.sensor < sensors.size())
        m.sensor = sensorWorldPose(toLocState(*last_with_readings_.truth), sensors[r.sensor].mount)
                       .position();
      if (r.update.match == MatchKind::kWall && r.update.feature_index < map.walls.size())
        m.wall = map.walls[r.update.feature_index].segment;
      else if (r.update.feature_index < map.points.size())
        m.point = map.points[r.update.feature_index].position;
      overlay.matches.push_back(m);
    }
  }
  if (drag_armed_ && drag_from_)
    overlay.drag_pose = canvas_.estimatorOverlay().drag_pose;
  canvas_.setEstimatorOverlay(std::move(overlay));
}

void LocalizationController::stepUpdate() {
  if (!runner_) {
    session_.report(EventLevel::kWarning,
                    tr("Localization: choose an estimator first (Localization menu)"));
    return;
  }
  if (session_.simulationControl() == nullptr) {
    session_.report(EventLevel::kWarning,
                    tr("Localization: single updates need the simulator (a linked robot's clock "
                       "is not ours)"));
    return;
  }
  stepping_ = true;
  const std::int64_t before = runner_->lastStep().index;
  for (int i = 0; i < kMaxStepsPerUpdate && runner_; ++i) {
    session_.singleStep();
    if (!runner_)
      break;
    const EstimatorStep& step = runner_->lastStep();
    if (step.index == before)
      continue;
    if (!usesStereo(*kind_) || !step.readings.empty()) {
      if (!usesStereo(*kind_))
        printStep(step);
      break;
    }
  }
  stepping_ = false;
}

void LocalizationController::printStep(const EstimatorStep& step) {
  const double gate = runner_->config().ekf.gate;
  if (step.encoder_gyro) {
    const DrStepResult& r = *step.encoder_gyro;
    session_.report(EventLevel::kSensor,
                    tr("enc+gyro update: Z = ψenc − φgyro = %1° (S = %2 deg², NIS %3 vs gate "
                       "%4): %5")
                        .arg(radToDeg(r.innovation_rad), 0, 'f', 4)
                        .arg(radToDeg(radToDeg(r.innovation_variance)), 0, 'g', 3)
                        .arg(r.nis, 0, 'f', 2)
                        .arg(gateText(runner_->config().encoder_gyro.gate_nis))
                        .arg(r.status == DrStepStatus::kUpdated    ? tr("applied")
                             : r.status == DrStepStatus::kGated    ? tr("gated out")
                             : r.status == DrStepStatus::kFallback ? tr("fallback (plain DR)")
                                                                   : tr("predicted only")));
  } else if (step.readings.empty()) {
    session_.report(EventLevel::kSensor, tr("DR step to %1").arg(formatPose(step.estimate)));
  }
  if (step.caster_periods > 0)
    session_.report(EventLevel::kSensor,
                    tr("caster J+ prediction: %1 periods, mean residual ‖e‖ = %2 mrad (%4), "
                       "Q = λ‖e‖ with λ = %3")
                        .arg(step.caster_periods)
                        .arg(1000.0 * step.caster_residual_sum / step.caster_periods, 0, 'f', 3)
                        .arg(runner_->config().caster_lambda, 0, 'g', 4)
                        .arg(step.caster_residual_from_robot ? tr("the robot's own")
                                                             : tr("of the re-split counts")));
  for (const StereoReadingRecord& r : step.readings) {
    QString text = tr("%1 sensor: ").arg(QString::fromLatin1(sensorName(r.sensor)));
    if (r.echo != EchoStatus::kEcho) {
      text += QString::fromLatin1(echoName(r.echo));
    } else if (r.update.match == MatchKind::kNone) {
      text += tr("echo (true reflector %1) — %2")
                  .arg(QString::fromStdString(r.true_reflector_id),
                       QString::fromLatin1(toString(r.update.status)));
    } else {
      const ScalarUpdate& d = r.update.distance;
      const ScalarUpdate& b = r.update.bearing;
      text += tr("matched %1 %2 (true %3): d = %4 m, innovation %5 mm, S = %6 mm², NIS %7 vs "
                 "gate %8")
                  .arg(QString::fromLatin1(toString(r.update.match)),
                       QString::fromStdString(r.update.feature_id),
                       QString::fromStdString(r.true_reflector_id))
                  .arg(r.update.measured_d_m, 0, 'f', 3)
                  .arg(1000.0 * d.innovation, 0, 'f', 1)
                  .arg(1e6 * d.s, 0, 'g', 3)
                  .arg(d.nis, 0, 'f', 2)
                  .arg(gateText(gate));
      if (b.attempted)
        text += tr("; θ innovation %1° (NIS %2)")
                    .arg(radToDeg(b.innovation), 0, 'f', 2)
                    .arg(b.nis, 0, 'f', 2);
      text += r.accepted ? tr(" — accepted") : tr(" — gated out");
    }
    session_.report(EventLevel::kSensor, text);
  }
  const LocCov& p = step.covariance;
  session_.report(EventLevel::kSensor,
                  tr("estimate %1, 1σ (%2 m, %3 m, %4°)")
                      .arg(formatPose(step.estimate))
                      .arg(std::sqrt(std::max(p(0, 0), 0.0)), 0, 'f', 3)
                      .arg(std::sqrt(std::max(p(1, 1), 0.0)), 0, 'f', 3)
                      .arg(radToDeg(std::sqrt(std::max(p(2, 2), 0.0))), 0, 'f', 2));
}

void LocalizationController::armInitialPoseDrag(bool armed) {
  drag_armed_ = armed;
  drag_from_.reset();
  {
    const QSignalBlocker a(drag_action_), b(drag_button_);
    drag_action_->setChecked(armed);
    drag_button_->setChecked(armed);
  }
  canvas_.setCursor(armed ? Qt::CrossCursor : Qt::ArrowCursor);
  if (armed)
    session_.report(EventLevel::kInfo,
                    tr("Localization: press on the map at the initial position and drag towards "
                       "the heading (Esc cancels)"));
  updateOverlay();
}

bool LocalizationController::eventFilter(QObject* watched, QEvent* event) {
  if (watched != &canvas_ || !drag_armed_)
    return QObject::eventFilter(watched, event);
  switch (event->type()) {
    case QEvent::MouseButtonPress: {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() != Qt::LeftButton)
        return false;
      drag_from_ = canvas_.widgetToWorld(e->position());
      widgets::EstimatorOverlay overlay = canvas_.estimatorOverlay();
      overlay.drag_pose = Pose2{drag_from_->x(), drag_from_->y(), session_.worldMap().start.theta};
      canvas_.setEstimatorOverlay(std::move(overlay));
      return true;
    }
    case QEvent::MouseMove: {
      if (!drag_from_)
        return false;
      auto* e = static_cast<QMouseEvent*>(event);
      const Vec2 to = canvas_.widgetToWorld(e->position());
      widgets::EstimatorOverlay overlay = canvas_.estimatorOverlay();
      const Vec2 d = to - *drag_from_;
      overlay.drag_pose = Pose2{drag_from_->x(), drag_from_->y(),
                                d.norm() * canvas_.pixelsPerMetre() >= kMinDrag_px
                                    ? std::atan2(d.y(), d.x())
                                    : session_.worldMap().start.theta};
      canvas_.setEstimatorOverlay(std::move(overlay));
      return true;
    }
    case QEvent::MouseButtonRelease: {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() != Qt::LeftButton || !drag_from_)
        return false;
      const Vec2 to = canvas_.widgetToWorld(e->position());
      const Vec2 d = to - *drag_from_;
      const double theta = d.norm() * canvas_.pixelsPerMetre() >= kMinDrag_px
                               ? std::atan2(d.y(), d.x())
                               : session_.worldMap().start.theta;
      const Pose2 pose{drag_from_->x(), drag_from_->y(), theta};
      armInitialPoseDrag(false);
      setInitialPose(pose);
      return true;
    }
    case QEvent::KeyPress:
      if (static_cast<QKeyEvent*>(event)->key() == Qt::Key_Escape) {
        armInitialPoseDrag(false);
        return true;
      }
      return false;
    default:
      return false;
  }
}

}  // namespace irgs::gui
