#include "widgets/replay/rerun_compare_view.hpp"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPainter>
#include <QPainterPath>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <tuple>

namespace irgs::widgets {

TrajectoryCanvas::TrajectoryCanvas(QWidget* parent) : MapCanvas(parent) {
  // The tracks replace the live trail; a re-run has no live sonar cones.
  setLayerVisible(Layer::kTrail, false);
  setLayerVisible(Layer::kSonar, false);
}

void TrajectoryCanvas::setTracks(std::vector<TrajectoryTrack> tracks) {
  tracks_ = std::move(tracks);
  update();
}

void TrajectoryCanvas::paintEvent(QPaintEvent* event) {
  MapCanvas::paintEvent(event);
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  if (!tracks_.empty()) {  // a backing for the legend, so walls under it do not cross the text
    int text_width = 0;
    for (const TrajectoryTrack& track : tracks_)
      text_width = std::max(text_width, p.fontMetrics().horizontalAdvance(track.label));
    QColor backing = palette().color(QPalette::Base);
    backing.setAlpha(220);
    p.setPen(Qt::NoPen);
    p.setBrush(backing);
    p.drawRoundedRect(QRectF(4, 4, 40 + text_width, 8 + 16.0 * static_cast<double>(tracks_.size())),
                      4, 4);
  }
  int legend_y = 18;
  for (const TrajectoryTrack& track : tracks_) {
    QPainterPath path;
    bool started = false;
    for (const irgs::Vec2& point : track.points) {
      if (!std::isfinite(point.x()) || !std::isfinite(point.y()))
        continue;
      const QPointF at = worldToWidget(point);
      if (started) {
        path.lineTo(at);
      } else {
        path.moveTo(at);
        started = true;
      }
    }
    QPen pen(track.colour, 2.0, track.style);
    pen.setCosmetic(true);
    p.setPen(pen);
    p.setBrush(Qt::NoBrush);
    p.drawPath(path);
    // Legend, top left.
    p.drawLine(QPointF(8, legend_y - 4), QPointF(30, legend_y - 4));
    p.setPen(palette().color(QPalette::WindowText));
    p.drawText(QPointF(36, legend_y), track.label);
    legend_y += 16;
  }
}

RerunCompareView::RerunCompareView(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* vertical = new QSplitter(Qt::Vertical, this);
  auto* maps = new QSplitter(Qt::Horizontal, vertical);
  for (auto [canvas, title, name] : {std::tuple{&recorded_, &recorded_title_, "recorded"},
                                     std::tuple{&rerun_, &rerun_title_, "rerun"}}) {
    auto* column = new QWidget(maps);
    auto* column_layout = new QVBoxLayout(column);
    column_layout->setContentsMargins(0, 0, 0, 0);
    *title = new QLabel(column);
    QFont bold = (*title)->font();
    bold.setBold(true);
    (*title)->setFont(bold);
    *canvas = new TrajectoryCanvas(column);
    (*canvas)->setObjectName(QString::fromLatin1(name) + QStringLiteral("Canvas"));
    column_layout->addWidget(*title);
    column_layout->addWidget(*canvas, 1);
    maps->addWidget(column);
  }
  table_ = new QTableWidget(vertical);
  table_->setObjectName(QStringLiteral("rerunMetrics"));
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->verticalHeader()->setVisible(false);
  table_->verticalHeader()->setDefaultSectionSize(table_->fontMetrics().height() + 6);
  table_->horizontalHeader()->setStretchLastSection(true);
  vertical->addWidget(maps);
  vertical->addWidget(table_);
  vertical->setStretchFactor(0, 3);
  vertical->setStretchFactor(1, 2);
  vertical->setSizes({560, 340});  // the table shows all its rows in a 900 px window
  layout->addWidget(vertical);

  connect(recorded_, &MapCanvas::viewChanged, this, [this] { syncView(*recorded_, *rerun_); });
  connect(rerun_, &MapCanvas::viewChanged, this, [this] { syncView(*rerun_, *recorded_); });
}

void RerunCompareView::syncView(const TrajectoryCanvas& from, TrajectoryCanvas& to) {
  if (syncing_)
    return;
  syncing_ = true;
  to.setView(from.viewCentre(), from.pixelsPerMetre());
  syncing_ = false;
}

void RerunCompareView::fitBoth() {
  syncing_ = true;  // each canvas's own resize/fit signals must not stop the other fitting
  recorded_->zoomToFit();
  rerun_->setView(recorded_->viewCentre(), recorded_->pixelsPerMetre());
  syncing_ = false;
}

void RerunCompareView::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  QTimer::singleShot(0, this, &RerunCompareView::fitBoth);
}

void RerunCompareView::setWorldMap(const irgs::WorldMap& map) {
  recorded_->setWorldMap(map);
  rerun_->setWorldMap(map);
}

void RerunCompareView::setRobotProfile(const irgs::RobotProfile& profile) {
  recorded_->setRobotProfile(profile);
  rerun_->setRobotProfile(profile);
}

void RerunCompareView::setRuns(const RerunSide& recorded, const RerunSide& rerun,
                               const std::vector<irgs::Pose2>& truth) {
  auto points = [](const std::vector<irgs::Pose2>& poses) {
    std::vector<irgs::Vec2> out;
    out.reserve(poses.size());
    for (const irgs::Pose2& p : poses)
      out.push_back(p.position());
    return out;
  };
  const TrajectoryTrack recorded_track{tr("recorded"), kRecordedColour,
                                       points(recorded.trajectory)};
  const TrajectoryTrack rerun_track{tr("re-run"), kRerunColour, points(rerun.trajectory)};
  const TrajectoryTrack truth_track{tr("truth"), kTruthColour, points(truth), Qt::DotLine};
  for (auto [canvas, side, own, other] :
       {std::tuple{recorded_, &recorded, &recorded_track, &rerun_track},
        std::tuple{rerun_, &rerun, &rerun_track, &recorded_track}}) {
    canvas->setGrid(side->grid);
    canvas->gridUpdated();
    std::vector<TrajectoryTrack> tracks{*own};
    tracks.push_back(*other);
    tracks.back().style = Qt::DashLine;
    if (!truth.empty())
      tracks.push_back(truth_track);
    canvas->setTracks(std::move(tracks));
    if (!side->trajectory.empty()) {
      irgs::TelemetrySample last;
      last.odometry_pose = side->trajectory.back();
      canvas->setRobotState(last);  // the robot where the run ended
    }
  }
  recorded_title_->setText(recorded.title);
  rerun_title_->setText(rerun.title);
  fitBoth();
}

void RerunCompareView::setMetrics(const QStringList& columns,
                                  const std::vector<QStringList>& rows) {
  table_->clear();
  table_->setColumnCount(static_cast<int>(columns.size()));
  table_->setHorizontalHeaderLabels(columns);
  table_->setRowCount(static_cast<int>(rows.size()));
  for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
    const QStringList& row = rows[static_cast<std::size_t>(r)];
    for (int c = 0; c < row.size() && c < columns.size(); ++c)
      table_->setItem(r, c, new QTableWidgetItem(row[c]));
  }
  table_->resizeColumnsToContents();
}

}  // namespace irgs::widgets
