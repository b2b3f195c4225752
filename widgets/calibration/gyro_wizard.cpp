#include "widgets/calibration/gyro_wizard.hpp"

#include <QApplication>
#include <QComboBox>
#include <QDoubleValidator>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QStackedWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <exception>

#include "core/calibration/profile_calibration.hpp"
#include "core/io/atomic_file.hpp"

namespace irgs::widgets {

namespace {

const char* const kCoefficientNames[6] = {"c0 (deg/s)", "c1 (deg/s/C)",   "c2 (deg/s/C^2)",
                                          "a1",         "a2 (1/(deg/s))", "a3 (1/(deg/s)^2)"};

double* coefficientField(GyroErrorModel& m, int i) {
  double* fields[6] = {&m.bias_c0_dps, &m.bias_c1_dps_per_c, &m.bias_c2_dps_per_c2,
                       &m.sf_a1,       &m.sf_a2_per_dps,     &m.sf_a3_per_dps2};
  return fields[i];
}

}  // namespace

GyroWizard::GyroWizard(RobotProfile profile, const QString& profile_file, QWidget* parent)
    : QDialog(parent), profile_(std::move(profile)) {
  setWindowTitle(tr("Gyro calibration — %1").arg(QString::fromStdString(profile_.name)));
  auto* layout = new QHBoxLayout(this);
  auto* left = new QVBoxLayout;
  layout->addLayout(left, 1);
  auto* right = new QVBoxLayout;
  layout->addLayout(right, 1);

  auto* intro = new QLabel(
      tr("Paper 001's procedure: the gyro at rest while the temperature cycles gives the bias "
         "b(T) (a line, or a quadratic); a rate table from -95 to 95 deg/s gives the cubic "
         "scale-factor correction p(x) (6). Calibrated rate = x + p(x) - b(T)."));
  intro->setWordWrap(true);
  left->addWidget(intro);

  auto* setup = new QGroupBox(tr("Procedure"));
  auto* form = new QFormLayout(setup);
  source_ = new QComboBox;
  source_->addItem(tr("Simulator with an injected gyro"));
  source_->addItem(tr("Logs from the robot (CSV)"));
  form->addRow(tr("Data from"), source_);
  order_ = new QComboBox;
  order_->addItem(tr("Line (as 001)"), 1);
  order_->addItem(tr("Quadratic"), 2);
  form->addRow(tr("Temperature bias"), order_);
  left->addWidget(setup);

  pages_ = new QStackedWidget;
  left->addWidget(pages_);
  auto* sim_page = new QGroupBox(tr("Injected gyro (AUTOGYRO noise level)"));
  auto* sim_form = new QFormLayout(sim_page);
  for (int i = 0; i < 6; ++i) {
    coefficient_[i] = new QLineEdit;
    auto* validator = new QDoubleValidator(coefficient_[i]);
    validator->setNotation(QDoubleValidator::ScientificNotation);
    validator->setLocale(QLocale::c());
    coefficient_[i]->setValidator(validator);
    sim_form->addRow(QString::fromLatin1(kCoefficientNames[i]), coefficient_[i]);
  }
  turn_ons_ = new QSpinBox;
  turn_ons_->setRange(1, 50);
  turn_ons_->setValue(4);
  turn_ons_->setToolTip(tr("Power-ups pooled: each has its own turn-on bias and scale factor"));
  sim_form->addRow(tr("Power-ups"), turn_ons_);
  seed_ = new QSpinBox;
  seed_->setRange(0, 1000000);
  seed_->setValue(5);
  sim_form->addRow(tr("Seed"), seed_);
  pages_->addWidget(sim_page);
  setInjected(autogyroErrorModel());

  auto* log_page = new QGroupBox(tr("Logs recorded on the robot"));
  auto* log_form = new QFormLayout(log_page);
  rate_log_ = new QLineEdit;
  rate_log_->setPlaceholderText(tr("CSV with true_dps, indicated_dps"));
  log_form->addRow(tr("Rate-table log"), rate_log_);
  rest_log_ = new QLineEdit;
  rest_log_->setPlaceholderText(tr("CSV with temperature_c, indicated_dps"));
  log_form->addRow(tr("Stationary log"), rest_log_);
  pages_->addWidget(log_page);

  run_ = new QPushButton(tr("Run calibration"));
  run_->setObjectName(QStringLiteral("gyroRun"));
  left->addWidget(run_);
  left->addStretch(1);

  table_ = new QTableWidget(0, 4);
  table_->setHorizontalHeaderLabels(
      {tr("Coefficient"), tr("Injected"), tr("Recovered"), tr("Error %")});
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->verticalHeader()->setVisible(false);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  right->addWidget(table_, 1);
  status_ = new QLabel;
  status_->setWordWrap(true);
  right->addWidget(status_);
  auto* out_row = new QHBoxLayout;
  output_ = new QLineEdit(profile_file);
  write_ = new QPushButton(tr("Write profile"));
  write_->setObjectName(QStringLiteral("gyroWriteProfile"));
  write_->setEnabled(false);
  out_row->addWidget(new QLabel(tr("Profile")));
  out_row->addWidget(output_, 1);
  out_row->addWidget(write_);
  right->addLayout(out_row);
  write_status_ = new QLabel;
  write_status_->setWordWrap(true);
  right->addWidget(write_status_);
  auto* close = new QPushButton(tr("Close"));
  connect(close, &QPushButton::clicked, this, &QDialog::close);
  right->addWidget(close, 0, Qt::AlignRight);

  connect(source_, &QComboBox::currentIndexChanged, pages_, &QStackedWidget::setCurrentIndex);
  connect(run_, &QPushButton::clicked, this, &GyroWizard::run);
  connect(write_, &QPushButton::clicked, this, &GyroWizard::writeProfile);
  resize(900, 520);
}

void GyroWizard::setSource(Source source) {
  source_->setCurrentIndex(static_cast<int>(source));
}

void GyroWizard::setInjected(const GyroErrorModel& model) {
  GyroErrorModel m = model;
  for (int i = 0; i < 6; ++i)
    coefficient_[i]->setText(QString::number(*coefficientField(m, i), 'g', 6));
}

GyroErrorModel GyroWizard::injected() const {
  GyroErrorModel m = autogyroErrorModel();
  for (int i = 0; i < 6; ++i) {
    bool ok = false;
    const double v = QLocale::c().toDouble(coefficient_[i]->text().trimmed(), &ok);
    if (ok)
      *coefficientField(m, i) = v;
  }
  return m;
}

void GyroWizard::setBiasOrder(int order) {
  order_->setCurrentIndex(order == 2 ? 1 : 0);
}

void GyroWizard::setPowerUps(int turn_ons) {
  turn_ons_->setValue(turn_ons);
}

void GyroWizard::setSeed(int seed) {
  seed_->setValue(seed);
}

void GyroWizard::setLogFiles(const QString& rate_table_csv, const QString& stationary_csv) {
  rate_log_->setText(rate_table_csv);
  rest_log_->setText(stationary_csv);
}

void GyroWizard::setOutputFile(const QString& path) {
  output_->setText(path);
}

QString GyroWizard::statusText() const {
  return status_->text();
}

void GyroWizard::run() {
  const int order = order_->currentData().toInt();
  result_.reset();
  std::optional<GyroErrorModel> injected_model;
  QApplication::setOverrideCursor(Qt::WaitCursor);
  try {
    if (source_->currentIndex() == static_cast<int>(Source::kSimulator)) {
      injected_model = injected();
      GyroProcedureConfig config;
      config.turn_ons = turn_ons_->value();
      config.seed = static_cast<std::uint64_t>(seed_->value());
      config.runs.bias_order = order;
      result_ = runGyroCalibrationInSimulator(*injected_model, config);
    } else {
      const ReadFileResult rate = readFile(rate_log_->text().trimmed().toStdString());
      const ReadFileResult rest = readFile(rest_log_->text().trimmed().toStdString());
      if (!rate.ok() || !rest.ok()) {
        status_->setText(QString::fromStdString(!rate.ok() ? rate.error : rest.error));
      } else {
        result_ = fitGyroCalibrationLogs(parseCalibrationCsv(rate.bytes),
                                         parseCalibrationCsv(rest.bytes), order);
      }
    }
  } catch (const std::exception& e) {
    status_->setText(tr("The calibration cannot run: %1").arg(QString::fromUtf8(e.what())));
  }
  QApplication::restoreOverrideCursor();
  showResult(injected_model);
}

void GyroWizard::showResult(const std::optional<GyroErrorModel>& injected_model) {
  write_->setEnabled(result_ && result_->ok);
  write_status_->clear();
  table_->setRowCount(0);
  if (!result_)
    return;
  QStringList notes;
  for (const std::string& d : result_->diagnostics)
    notes << QString::fromStdString(d);
  if (!result_->ok) {
    status_->setText(tr("The fits failed. ") + notes.join(QLatin1Char(' ')));
    return;
  }
  const int order = order_->currentData().toInt();
  const auto addRow = [&](const QString& name, std::optional<double> injected, double recovered,
                          std::optional<double> relative) {
    const int row = table_->rowCount();
    table_->insertRow(row);
    table_->setItem(row, 0, new QTableWidgetItem(name));
    table_->setItem(
        row, 1, new QTableWidgetItem(injected ? QString::number(*injected, 'g', 5) : QString()));
    table_->setItem(row, 2, new QTableWidgetItem(QString::number(recovered, 'g', 5)));
    table_->setItem(
        row, 3,
        new QTableWidgetItem(relative ? QString::number(100.0 * *relative, 'f', 2) : QString()));
  };
  const double mid = 0.5 * (result_->rest_min_temperature_c + result_->rest_max_temperature_c);
  if (injected_model) {
    for (const GyroCoefficientCheck& c :
         compareGyroCalibration(result_->calibration, *injected_model, order, mid))
      addRow(QString::fromStdString(c.name), c.injected, c.recovered, c.relative_error);
  } else {
    const GyroCalibration& c = result_->calibration;
    addRow(QStringLiteral("a1"), std::nullopt, c.scale.a1, std::nullopt);
    addRow(QStringLiteral("a2"), std::nullopt, c.scale.a2_per_dps, std::nullopt);
    addRow(QStringLiteral("a3"), std::nullopt, c.scale.a3_per_dps2, std::nullopt);
    addRow(QStringLiteral("c0"), std::nullopt, c.bias.c0_dps, std::nullopt);
    addRow(QStringLiteral("c1"), std::nullopt, c.bias.c1_dps_per_c, std::nullopt);
    if (order == 2)
      addRow(QStringLiteral("c2"), std::nullopt, c.bias.c2_dps_per_c2, std::nullopt);
  }
  status_->setText(tr("%1 rate-table and %2 stationary samples (%3 .. %4 C); rms residuals "
                      "%5 and %6 deg/s. %7")
                       .arg(result_->rate_samples)
                       .arg(result_->rest_samples)
                       .arg(result_->rest_min_temperature_c, 0, 'f', 1)
                       .arg(result_->rest_max_temperature_c, 0, 'f', 1)
                       .arg(result_->scale_fit.rms_residual_dps, 0, 'g', 3)
                       .arg(result_->bias_fit.rms_residual_dps, 0, 'g', 3)
                       .arg(notes.join(QLatin1Char(' '))));
}

bool GyroWizard::writeProfile() {
  if (!result_ || !result_->ok)
    return false;
  const QString path = output_->text().trimmed();
  try {
    const RobotProfile calibrated = applyGyroCalibration(profile_, result_->calibration);
    if (const auto error = saveCalibratedProfile(calibrated, path.toStdString())) {
      write_status_->setText(tr("Not written: %1").arg(QString::fromStdString(*error)));
      return false;
    }
  } catch (const std::exception& e) {
    write_status_->setText(tr("Not written: %1").arg(QString::fromUtf8(e.what())));
    return false;
  }
  write_status_->setText(
      tr("Wrote %1. The calibration applies when the profile is next loaded.").arg(path));
  emit profileWritten(path);
  return true;
}

}  // namespace irgs::widgets
