#pragma once
// The side-by-side view of a re-run (docs/gui.md, "Re-run with parameters"): the recorded run's
// map and the re-run's map in two map canvases whose views move together, each with both
// trajectories drawn over it (its own solid, the other dashed, the truth dotted when there is
// one), and a metrics table underneath. It only shows: the application computes the runs and
// the metrics (app/recording/rerun_engine.hpp) and passes grids, poses and table rows in.

#include <QColor>
#include <QString>
#include <QStringList>
#include <QWidget>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/world/world_map.hpp"
#include "widgets/canvas/map_canvas.hpp"

class QLabel;
class QTableWidget;

namespace irgs::widgets {

struct TrajectoryTrack {
  QString label;
  QColor colour;
  std::vector<irgs::Vec2> points;  // world metres, in time order
  Qt::PenStyle style = Qt::SolidLine;
};

// A map canvas with polylines drawn over everything (the canvas's own trail follows one live
// robot; a comparison needs several fixed tracks).
class TrajectoryCanvas : public MapCanvas {
  Q_OBJECT

 public:
  explicit TrajectoryCanvas(QWidget* parent = nullptr);
  void setTracks(std::vector<TrajectoryTrack> tracks);
  const std::vector<TrajectoryTrack>& tracks() const { return tracks_; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  std::vector<TrajectoryTrack> tracks_;
};

struct RerunSide {
  QString title;                              // "Recorded (grid 0.01 m)"
  const irgs::OccupancyGrid* grid = nullptr;  // must outlive the view
  std::vector<irgs::Pose2> trajectory;
};

class RerunCompareView : public QWidget {
  Q_OBJECT

 public:
  static inline const QColor kRecordedColour{30, 110, 230};
  static inline const QColor kRerunColour{230, 90, 20};
  static inline const QColor kTruthColour{20, 150, 60};

  explicit RerunCompareView(QWidget* parent = nullptr);

  void setWorldMap(const irgs::WorldMap& map);
  void setRobotProfile(const irgs::RobotProfile& profile);
  // Both sides and the truth (empty: none); fits both views to the maps.
  void setRuns(const RerunSide& recorded, const RerunSide& rerun,
               const std::vector<irgs::Pose2>& truth = {});
  // Rows of the metrics table: the metric's name, then one cell per column of `columns`.
  void setMetrics(const QStringList& columns, const std::vector<QStringList>& rows);

  // Fits the recorded map, trajectories included, and gives the re-run view the same view.
  void fitBoth();

  TrajectoryCanvas& recordedCanvas() const { return *recorded_; }
  TrajectoryCanvas& rerunCanvas() const { return *rerun_; }
  QTableWidget& metricsTable() const { return *table_; }

 protected:
  // The canvases only have their real size once the window is shown: fit then.
  void showEvent(QShowEvent* event) override;

 private:
  void syncView(const TrajectoryCanvas& from, TrajectoryCanvas& to);

  TrajectoryCanvas* recorded_ = nullptr;
  TrajectoryCanvas* rerun_ = nullptr;
  QLabel* recorded_title_ = nullptr;
  QLabel* rerun_title_ = nullptr;
  QTableWidget* table_ = nullptr;
  bool syncing_ = false;
};

}  // namespace irgs::widgets
