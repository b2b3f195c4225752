#pragma once
// File > Export (issue 6, item 8), at any moment of a live session or a replay (a replay plays
// through the same session): the map view as PNG or SVG (what the canvas shows: map, sonar grid,
// trail, robot), the session's sonar grid as a ROS map (PGM + YAML) and a session summary
// (duration, distance, link quality, events) as Markdown or HTML. The summary of the running
// session is collected here as it goes: the odometry path length from the shown samples, the
// warnings/errors/link events of the console, the link statistics at export time. A recording
// file's summary comes from `irgs-summary` (app/recording/session_summary.hpp).

#include <QObject>
#include <QString>
#include <optional>

#include "app/recording/session_summary.hpp"

class QMainWindow;
class QMenu;

namespace irgs::widgets {
class MapCanvas;
}

namespace irgs {
struct TelemetrySample;
}

namespace irgs::gui {

class LinkController;
class SessionController;
enum class EventLevel;

class ExportActions : public QObject {
  Q_OBJECT

 public:
  // Adds the "Export" submenu to the menu named "fileMenu" of `window` (before its last
  // separator), or to the window when there is none.
  ExportActions(SessionController& session, widgets::MapCanvas& canvas, LinkController& link,
                QMainWindow& window);

  // Each returns an error message, empty on success.
  QString exportMapPng(const QString& path) const;
  QString exportMapSvg(const QString& path) const;
  QString exportRosMap(const QString& yaml_path) const;
  QString exportSummary(const QString& path) const;
  recording::SessionSummary liveSummary() const;

  QMenu& menu() const { return *menu_; }

 private:
  void onSample(const TelemetrySample& sample);
  void onConsole(EventLevel level, double time_s, const QString& text);
  void choose(const QString& title, const QString& filter, const QString& suggested,
              QString (ExportActions::*action)(const QString&) const);

  SessionController& session_;
  widgets::MapCanvas& canvas_;
  LinkController& link_;
  QMainWindow& window_;
  QMenu* menu_ = nullptr;
  double distance_m_ = 0.0;
  std::optional<std::pair<double, double>> last_xy_;
  std::vector<recording::SummaryEvent> events_;
  std::map<std::string, std::size_t> event_counts_;
  std::uint32_t link_losses_ = 0;
};

}  // namespace irgs::gui
