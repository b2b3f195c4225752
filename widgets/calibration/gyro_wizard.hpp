#pragma once
// The gyro calibration wizard (paper 001_…, docs/calibration.md): a stationary run against
// temperature (bias line or quadratic) and rate-table runs (the cubic scale-factor curve (6)),
// fitted by least squares (core/calibration/gyro_calibration_run.hpp) and written back to the
// robot profile atomically.
//
// Two sources: the simulator with an injected gyro (the AUTOGYRO level of 001 by default, every
// coefficient editable), which also shows injected against recovered; or logs recorded on a real
// robot (a rate-table CSV and a stationary CSV, the columns parseCalibrationCsv reads).

#include <QDialog>
#include <QString>
#include <optional>

#include "core/calibration/gyro_calibration_run.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/sim/gyro_sim.hpp"

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;
class QStackedWidget;
class QTableWidget;

namespace irgs::widgets {

class GyroWizard : public QDialog {
  Q_OBJECT

 public:
  enum class Source { kSimulator = 0, kLogs = 1 };

  GyroWizard(RobotProfile profile, const QString& profile_file, QWidget* parent = nullptr);

  void setSource(Source source);
  void setInjected(const GyroErrorModel& model);
  GyroErrorModel injected() const;  // the edited coefficients on the AUTOGYRO noise model
  void setBiasOrder(int order);     // 1 line, 2 quadratic
  void setPowerUps(int turn_ons);
  void setSeed(int seed);
  void setLogFiles(const QString& rate_table_csv, const QString& stationary_csv);
  void setOutputFile(const QString& path);

  // Runs the chosen procedure (blocking: the simulated one takes a few seconds).
  void run();
  bool writeProfile();

  const std::optional<GyroProcedureResult>& result() const { return result_; }
  // Rows of the results table: name, injected (empty for logs), recovered, error %.
  QTableWidget* resultsTable() const { return table_; }
  QString statusText() const;

 signals:
  void profileWritten(const QString& path);

 private:
  void showResult(const std::optional<GyroErrorModel>& injected);

  RobotProfile profile_;
  std::optional<GyroProcedureResult> result_;

  QComboBox* source_ = nullptr;
  QStackedWidget* pages_ = nullptr;
  QLineEdit* coefficient_[6] = {};  // c0, c1, c2, a1, a2, a3
  QSpinBox* turn_ons_ = nullptr;
  QSpinBox* seed_ = nullptr;
  QComboBox* order_ = nullptr;
  QLineEdit* rate_log_ = nullptr;
  QLineEdit* rest_log_ = nullptr;
  QPushButton* run_ = nullptr;
  QTableWidget* table_ = nullptr;
  QLabel* status_ = nullptr;
  QLineEdit* output_ = nullptr;
  QPushButton* write_ = nullptr;
  QLabel* write_status_ = nullptr;
};

}  // namespace irgs::widgets
