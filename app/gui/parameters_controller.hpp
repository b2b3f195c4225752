#pragma once
// The "Parameters" dock (issue 6, item 5): one table for
//   * the robot profile's values (geometry, limits, sensor mounts; read-only here: the profile
//     file is the source, the calibration wizards write it);
//   * the algorithm parameters of this session — mapping (grid resolution, sonar valid
//     distance), the localization EKF (gates epsilon1/epsilon2/g, measurement and process
//     noise, stereo period) and planning (turn quantum, A* budget, clearance) — applied to the
//     running session at once and saved per robot profile (QSettings "parameters/<robot>/...");
//   * the firmware parameters of a linked robot over the MAVLink parameter protocol: "Read"
//     asks for all, an edited value is written after a confirmation and the robot's answer
//     (accepted / rejected / timed out) is shown and logged.
// Toggled from View > Parameters (Ctrl+Shift+A).

#include <QObject>
#include <QString>
#include <functional>

class QDockWidget;
class QLabel;
class QMainWindow;
class QPushButton;
class QSettings;
class QTimer;

namespace irgs::widgets {
class ParameterTable;
}

namespace irgs::gui {

class LinkController;
class LocalizationController;
class PlanningController;
class SessionController;

class ParametersController : public QObject {
  Q_OBJECT

 public:
  static constexpr int kPollInterval_ms = 100;
  static inline const QString kProfileSection = QStringLiteral("Robot profile");
  static inline const QString kMappingSection = QStringLiteral("Mapping");
  static inline const QString kLocalizationSection = QStringLiteral("Localization (EKF)");
  static inline const QString kPlanningSection = QStringLiteral("Planning");
  static inline const QString kFirmwareSection = QStringLiteral("Firmware (MAVLink PARAM)");

  // Restores the saved algorithm parameters of the session's robot and applies them.
  ParametersController(SessionController& session, LocalizationController& localization,
                       PlanningController& planning, LinkController& link, QSettings& settings,
                       QMainWindow& window);
  ~ParametersController() override;

  widgets::ParameterTable& table() const { return *table_; }
  QDockWidget& dock() const { return *dock_; }
  QString statusText() const;

  // Asked before a firmware write with a sentence describing it; the default shows a
  // QMessageBox. Tests replace it.
  using Confirm = std::function<bool(const QString& question)>;
  void setConfirm(Confirm confirm) { confirm_ = std::move(confirm); }

  // Reads every firmware parameter of the linked robot (false when none is linked).
  bool readFirmwareParameters();
  // Writes a firmware parameter; `ask` first asks the Confirm hook. False when nothing was sent
  // (no link, declined, invalid): statusText() says why.
  bool writeFirmwareParameter(const QString& name, double value, bool ask);
  // Edits a parameter as the user would (applies / writes after confirmation).
  void edit(const QString& key, double value);
  // Picks up firmware answers now (also runs every kPollInterval_ms while linked).
  void poll();

 private:
  void buildProfileSection();
  void buildAlgorithmSections();
  void applyAlgorithmParameter(const QString& key, double value, bool save);
  void applyMapping();
  void applyLocalization();
  void applyPlanning();
  void refreshFirmwareSection();
  void onLinkedChanged(bool linked);
  QString settingsGroup() const;

  SessionController& session_;
  LocalizationController& localization_;
  PlanningController& planning_;
  LinkController& link_;
  QSettings& settings_;
  QDockWidget* dock_ = nullptr;
  widgets::ParameterTable* table_ = nullptr;
  QLabel* status_ = nullptr;
  QPushButton* read_button_ = nullptr;
  QTimer* poll_timer_ = nullptr;
  Confirm confirm_;
  int shown_firmware_count_ = -1;
  bool reading_ = false;
};

}  // namespace irgs::gui
