#include "app/gui/export_actions.hpp"

#include <QAction>
#include <QFileDialog>
#include <QFileInfo>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPainter>
#include <QPixmap>
#include <QSvgGenerator>
#include <cmath>
#include <filesystem>

#include "app/gui/link_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/mapping/grid_export.hpp"
#include "widgets/canvas/map_canvas.hpp"

namespace irgs::gui {
namespace {

const char* kindOf(EventLevel level) {
  switch (level) {
    case EventLevel::kInfo:
      return "info";
    case EventLevel::kWarning:
      return "warning";
    case EventLevel::kError:
      return "error";
    case EventLevel::kSensor:
      return "sensor";
  }
  return "info";
}

}  // namespace

ExportActions::ExportActions(SessionController& session, widgets::MapCanvas& canvas,
                             LinkController& link, QMainWindow& window)
    : QObject(&window), session_(session), canvas_(canvas), link_(link), window_(window) {
  menu_ = new QMenu(tr("E&xport"), &window);
  menu_->setObjectName(QStringLiteral("exportMenu"));
  menu_->addAction(tr("Map View as &PNG…"), this, [this] {
    choose(tr("Export Map View as PNG"), tr("PNG image (*.png)"), QStringLiteral("map.png"),
           &ExportActions::exportMapPng);
  });
  menu_->addAction(tr("Map View as &SVG…"), this, [this] {
    choose(tr("Export Map View as SVG"), tr("SVG drawing (*.svg)"), QStringLiteral("map.svg"),
           &ExportActions::exportMapSvg);
  });
  menu_->addAction(tr("Sonar Grid as &ROS Map…"), this, [this] {
    choose(tr("Export Sonar Grid as ROS Map"), tr("ROS map YAML (*.yaml)"),
           QStringLiteral("sonar_map.yaml"), &ExportActions::exportRosMap);
  });
  menu_->addAction(tr("Session &Summary…"), this, [this] {
    choose(tr("Export Session Summary"), tr("Markdown (*.md);;HTML (*.html)"),
           QStringLiteral("session_summary.md"), &ExportActions::exportSummary);
  });
  QMenu* file = window.menuBar()->findChild<QMenu*>(QStringLiteral("fileMenu"));
  if (file != nullptr) {
    // Before "Quit" (the last action, after a separator).
    const QList<QAction*> actions = file->actions();
    QAction* before = actions.size() >= 2 ? actions[actions.size() - 2] : nullptr;
    if (before != nullptr && !before->isSeparator())
      before = actions.back();
    file->insertMenu(before, menu_);
  } else {
    window.menuBar()->addMenu(menu_);
  }

  connect(&session_, &SessionController::robotStateChanged, this, &ExportActions::onSample);
  connect(&session_, &SessionController::consoleEvent, this, &ExportActions::onConsole);
  connect(&link_, &LinkController::healthChanged, this, [this](const widgets::LinkHealth& h) {
    link_losses_ = std::max(link_losses_, h.link_losses);
  });
}

void ExportActions::onSample(const TelemetrySample& sample) {
  const std::pair<double, double> xy{sample.odometry_pose.x, sample.odometry_pose.y};
  if (last_xy_) {
    const double step = std::hypot(xy.first - last_xy_->first, xy.second - last_xy_->second);
    // A jump (robot reset to the start, a robot restart) is not travel.
    if (std::isfinite(step) && step < 1.0)
      distance_m_ += step;
  }
  last_xy_ = xy;
}

void ExportActions::onConsole(EventLevel level, double time_s, const QString& text) {
  const std::string kind = kindOf(level);
  ++event_counts_[kind];
  if (level == EventLevel::kWarning || level == EventLevel::kError)
    events_.push_back({time_s, kind, text.toStdString()});
}

recording::SessionSummary ExportActions::liveSummary() const {
  recording::SessionSummary s;
  s.source = session_.worldSource().isEmpty()
                 ? std::string("live session")
                 : "live session on " + session_.worldSource().toStdString();
  if (Robot* robot = session_.robot())
    s.meta["robot"] = robot->describe();
  s.meta["robot profile"] = session_.profile().name;
  s.duration_s = session_.displayTime_s();
  s.distance_m = distance_m_;
  s.distance_from = "odometry as shown";
  s.event_counts = event_counts_;
  s.events = events_;
  if (link_.linked()) {
    const widgets::LinkHealth h = link_.health();
    recording::SummaryLink l;
    l.crc_errors = h.crc_errors;
    l.sequence_gaps = h.sequence_errors;
    l.other_errors = h.other_errors;
    l.loss_percent = h.loss_percent;
    l.link_losses = std::max<std::uint64_t>(link_losses_, h.link_losses);
    s.link = l;
    s.meta["link"] = h.link.toStdString();
  }
  return s;
}

QString ExportActions::exportMapPng(const QString& path) const {
  const QPixmap pixmap = canvas_.grab();
  if (pixmap.isNull() || !pixmap.save(path, "PNG"))
    return tr("cannot write %1").arg(path);
  return {};
}

QString ExportActions::exportMapSvg(const QString& path) const {
  QSvgGenerator svg;
  svg.setFileName(path);
  svg.setSize(canvas_.size());
  svg.setViewBox(QRect(QPoint(0, 0), canvas_.size()));
  svg.setTitle(tr("IRGS map view"));
  svg.setDescription(session_.worldSource());
  {
    QPainter painter;
    if (!painter.begin(&svg))
      return tr("cannot write %1").arg(path);
    canvas_.render(&painter, QPoint(), QRegion(), QWidget::DrawChildren);
  }
  if (!QFileInfo::exists(path) || QFileInfo(path).size() == 0)
    return tr("cannot write %1").arg(path);
  return {};
}

QString ExportActions::exportRosMap(const QString& yaml_path) const {
  GridExportThresholds thresholds;
  thresholds.padding_cells = 5;
  if (const auto error = saveGridAsRosMap(
          session_.grid(), std::filesystem::path(yaml_path.toStdString()), thresholds))
    return QString::fromStdString(*error);
  return {};
}

QString ExportActions::exportSummary(const QString& path) const {
  const std::string error = recording::writeSummary(liveSummary(), path.toStdString());
  return QString::fromStdString(error);
}

void ExportActions::choose(const QString& title, const QString& filter, const QString& suggested,
                           QString (ExportActions::*action)(const QString&) const) {
  const QString path = QFileDialog::getSaveFileName(&window_, title, suggested, filter);
  if (path.isEmpty())
    return;
  const QString error = (this->*action)(path);
  if (!error.isEmpty()) {
    QMessageBox::warning(&window_, title, error);
    return;
  }
  session_.report(EventLevel::kInfo, tr("Exported %1").arg(path));
}

}  // namespace irgs::gui
