#include "app/gui/calibration_controller.hpp"

#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <exception>
#include <memory>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "widgets/calibration/gyro_wizard.hpp"
#include "widgets/calibration/umbmark_wizard.hpp"

namespace irgs::gui {

CalibrationController::CalibrationController(QMainWindow& window, SessionController& session,
                                             QString profile_file, QObject* parent)
    : QObject(parent), window_(window), session_(session), profile_file_(std::move(profile_file)) {
  behaviours_ = new BehaviourController(session_, this);
  connect(behaviours_, &BehaviourController::finished, this,
          &CalibrationController::onSquareFinished);
  menu_ = new QMenu(tr("&Calibrate"), &window_);
  menu_->setObjectName(QStringLiteral("calibrateMenu"));
  menu_->addAction(tr("&Odometry (UMBmark)…"), this, [this] { openUmbmarkWizard(); });
  menu_->addAction(tr("&Gyro…"), this, [this] { openGyroWizard(); });
  // Before Help, which stays last.
  QAction* before = nullptr;
  for (QAction* top : window_.menuBar()->actions())
    if (top->menu() != nullptr && top->menu()->title().remove(QLatin1Char('&')) == tr("Help"))
      before = top;
  if (before != nullptr)
    window_.menuBar()->insertMenu(before, menu_);
  else
    window_.menuBar()->addMenu(menu_);
}

CalibrationController::~CalibrationController() {
  delete umbmark_.data();
  delete gyro_.data();
}

widgets::UmbmarkWizard* CalibrationController::openUmbmarkWizard() {
  if (!umbmark_) {
    umbmark_ = new widgets::UmbmarkWizard(session_.profile(), profile_file_, &window_);
    umbmark_->setWindowFlag(Qt::Window);
    connect(umbmark_, &widgets::UmbmarkWizard::driveSquareRequested, this,
            &CalibrationController::driveSquare);
    connect(umbmark_, &widgets::UmbmarkWizard::profileWritten, this, [this](const QString& path) {
      session_.report(EventLevel::kInfo,
                      tr("UMBmark corrections written to %1 (used from the next start)").arg(path));
    });
  }
  umbmark_->show();
  umbmark_->raise();
  return umbmark_;
}

widgets::GyroWizard* CalibrationController::openGyroWizard() {
  if (!gyro_) {
    gyro_ = new widgets::GyroWizard(session_.profile(), profile_file_, &window_);
    gyro_->setWindowFlag(Qt::Window);
    connect(gyro_, &widgets::GyroWizard::profileWritten, this, [this](const QString& path) {
      session_.report(EventLevel::kInfo,
                      tr("Gyro calibration written to %1 (used from the next start)").arg(path));
    });
  }
  gyro_->show();
  gyro_->raise();
  return gyro_;
}

bool CalibrationController::squareRunning() const {
  return behaviours_->running();
}

void CalibrationController::driveSquare(const UmbmarkSquareConfig& config) {
  const auto refuse = [this](const QString& why) {
    if (umbmark_)
      umbmark_->robotRunFailed(why);
  };
  if (behaviours_->running())
    return refuse(tr("a square is already being driven"));
  std::shared_ptr<UmbmarkSquareBehaviour> behaviour;
  try {
    behaviour = std::make_shared<UmbmarkSquareBehaviour>(session_.profile(), config);
  } catch (const std::exception& e) {
    return refuse(QString::fromUtf8(e.what()));
  }
  square_ = behaviour.get();
  square_direction_ = config.direction;
  if (!behaviours_->start(behaviour, tr("UMBmark square"))) {
    square_ = nullptr;
    return refuse(tr("another behaviour or drive script is driving the robot; stop it first"));
  }
  session_.report(EventLevel::kInfo, tr("UMBmark: driving a %1 m %2 square")
                                         .arg(config.side_m)
                                         .arg(QString::fromLatin1(toString(config.direction))));
}

void CalibrationController::onSquareFinished(bool failed, const QString& message) {
  UmbmarkSquareBehaviour* square = square_;
  square_ = nullptr;
  if (square == nullptr || !umbmark_)
    return;
  session_.report(failed ? EventLevel::kWarning : EventLevel::kInfo, message);
  if (failed) {
    umbmark_->robotRunFailed(message);
    return;
  }
  std::optional<Vec2> truth;
  if (square->truePose())
    truth = square->truePose()->position();
  umbmark_->addRobotRun(square_direction_, square->odometryPose().position(), truth);
}

}  // namespace irgs::gui
