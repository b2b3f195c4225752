#pragma once
// The plots dock in the main window (issue 6, item 4): a PlotDataHub fed from the session —
// every numeric field of each telemetry sample the session shows, the command in force, the
// running estimator's state (LocalizationController) and the link statistics while a robot is
// linked, with every numeric field of the robot's MAVLink messages ("MAVLink/<message>/<field>",
// "MAVLink/<message>/<instance>/<field>" for a multi-instance message such as DISTANCE_SENSOR;
// live or replayed) — and the PlotsDock showing it, toggled from View > Plots (Ctrl+Shift+P).
//
// Samples are recorded as the session emits robotStateChanged (every tick, plus intermediate
// samples at fast speeds), so a field is plotted at the GUI's update rate, not necessarily at
// the robot's sample rate; the series keep ~20 minutes at 50 Hz per field. MAVLink fields are
// recorded at their messages' own time stamps (the robot clock, on the samples' time axis), each
// stream thinned to at most 25 Hz (guiMessageSampling), kMavlinkCapacity samples per field.

#include <QObject>
#include <QString>
#include <QStringList>
#include <cstdint>
#include <unordered_map>

class QDockWidget;
class QMainWindow;

namespace irgs {
struct TelemetrySample;
}

namespace irgs::comms {
struct MessageSample;
}

namespace irgs::widgets {
class PlotDataHub;
class PlotsDock;
struct LinkHealth;
}  // namespace irgs::widgets

namespace irgs::gui {

class LinkController;
class LocalizationController;
class SessionController;

class PlotsController : public QObject {
  Q_OBJECT

 public:
  static constexpr std::size_t kMavlinkCapacity = 32768;  // ~22 min at 25 Hz

  // The key of field `index` of a message stream: "MAVLink/DISTANCE_SENSOR/id 3/current_distance",
  // arrays by element ("MAVLink/IRGS_SONAR_SCAN/range[4]").
  static QString mavlinkKey(const comms::MessageSample& message, std::size_t index);

  // Adds the dock (hidden) to `window` and its toggle to the menu named "viewMenu" when there
  // is one. Everything must outlive the controller. Construct after `localization` so the
  // estimator has seen a sample before its state is recorded.
  PlotsController(SessionController& session, LocalizationController& localization,
                  LinkController& link, QMainWindow& window);
  ~PlotsController() override;

  widgets::PlotDataHub& hub() const { return *hub_; }
  widgets::PlotsDock& plots() const { return *plots_; }
  QDockWidget& dock() const { return *dock_; }

 private:
  void onSample(const TelemetrySample& sample);
  void onHealth(const widgets::LinkHealth& health);
  // Records the linked robot's decoded messages (each GUI tick).
  void takeMessages();

  struct StreamKeys {
    QStringList keys;  // one per field of the message's table
    QStringList units;
  };

  SessionController& session_;
  LocalizationController& localization_;
  LinkController& link_;
  std::unordered_map<std::uint64_t, StreamKeys> stream_keys_;  // by message id and instance
  widgets::PlotDataHub* hub_ = nullptr;
  widgets::PlotsDock* plots_ = nullptr;
  QDockWidget* dock_ = nullptr;
  std::int64_t last_estimator_index_ = -1;
  const void* last_runner_ = nullptr;
};

}  // namespace irgs::gui
