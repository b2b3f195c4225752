#include "widgets/calibration/umbmark_wizard.hpp"

#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QStackedWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>
#include <exception>

#include "core/calibration/profile_calibration.hpp"
#include "widgets/calibration/umbmark_path_view.hpp"

namespace irgs::widgets {

namespace {

// Robot-run table columns.
enum Column { kDirection, kOdoX, kOdoY, kMeasX, kMeasY, kColumnCount };

QDoubleSpinBox* ratioBox(double value) {
  auto* box = new QDoubleSpinBox;
  box->setRange(0.8, 1.25);
  box->setDecimals(4);
  box->setSingleStep(0.005);
  box->setValue(value);
  return box;
}

QString number(double v, int decimals = 4) {
  return QString::number(v, 'f', decimals);
}

}  // namespace

UmbmarkWizard::UmbmarkWizard(RobotProfile profile, const QString& profile_file, QWidget* parent)
    : QDialog(parent), profile_(std::move(profile)) {
  setWindowTitle(
      tr("UMBmark odometry calibration — %1").arg(QString::fromStdString(profile_.name)));
  auto* layout = new QHBoxLayout(this);
  auto* left = new QVBoxLayout;
  layout->addLayout(left, 3);
  auto* right = new QVBoxLayout;
  layout->addLayout(right, 2);

  auto* intro = new QLabel(
      tr("The robot drives a square on its own odometry, clockwise and counter-clockwise, and "
         "stops where it believes it started. The return errors give the wheel-diameter ratio "
         "E_d and the wheelbase ratio E_b (Borenstein & Feng, UMBmark)."));
  intro->setWordWrap(true);
  left->addWidget(intro);

  auto* setup = new QGroupBox(tr("Procedure"));
  auto* setup_form = new QFormLayout(setup);
  source_ = new QComboBox;
  source_->addItem(tr("Simulator with injected errors"));
  source_->addItem(tr("Session robot (measured end positions)"));
  source_->setObjectName(QStringLiteral("umbmarkSource"));
  setup_form->addRow(tr("Runs from"), source_);
  side_ = new QDoubleSpinBox;
  side_->setRange(0.5, 20.0);
  side_->setDecimals(2);
  side_->setSuffix(tr(" m"));
  side_->setValue(4.0);
  setup_form->addRow(tr("Square side"), side_);
  left->addWidget(setup);

  pages_ = new QStackedWidget;
  left->addWidget(pages_);

  // Simulator page.
  auto* sim_page = new QGroupBox(tr("Injected errors (the physical robot)"));
  auto* sim_form = new QFormLayout(sim_page);
  inject_ed_ = ratioBox(1.01);
  inject_ed_->setToolTip(tr("E_d = D_R / D_L, right wheel diameter over left"));
  sim_form->addRow(tr("Wheel-diameter ratio E_d"), inject_ed_);
  inject_eb_ = ratioBox(1.03);
  inject_eb_->setToolTip(tr("true wheelbase / profile wheelbase"));
  sim_form->addRow(tr("Wheelbase ratio E_b"), inject_eb_);
  inject_slip_ = new QDoubleSpinBox;
  inject_slip_->setRange(0.0, 0.05);
  inject_slip_->setDecimals(4);
  inject_slip_->setSingleStep(0.001);
  inject_slip_->setValue(0.002);
  sim_form->addRow(tr("Random slip (relative)"), inject_slip_);
  runs_ = new QSpinBox;
  runs_->setRange(1, 20);
  runs_->setValue(5);
  sim_form->addRow(tr("Runs per direction"), runs_);
  seed_ = new QSpinBox;
  seed_->setRange(0, 1000000);
  seed_->setValue(11);
  sim_form->addRow(tr("Seed"), seed_);
  run_sim_ = new QPushButton(tr("Run in simulator"));
  run_sim_->setObjectName(QStringLiteral("umbmarkRunSimulation"));
  sim_form->addRow(run_sim_);
  pages_->addWidget(sim_page);

  // Robot page.
  auto* robot_page = new QGroupBox(tr("Runs on the session robot"));
  auto* robot_layout = new QVBoxLayout(robot_page);
  auto* robot_help = new QLabel(
      tr("Place the robot with room for the square (left of it for counter-clockwise, right for "
         "clockwise), mark its start, drive a square, then measure where it stopped in the start "
         "frame (x forward, y left, metres) and enter it. At least one run each way; five each "
         "is the paper's procedure."));
  robot_help->setWordWrap(true);
  robot_layout->addWidget(robot_help);
  auto* drive_row = new QHBoxLayout;
  drive_cw_ = new QPushButton(tr("Drive clockwise square"));
  drive_ccw_ = new QPushButton(tr("Drive counter-clockwise square"));
  drive_cw_->setObjectName(QStringLiteral("umbmarkDriveCw"));
  drive_ccw_->setObjectName(QStringLiteral("umbmarkDriveCcw"));
  drive_row->addWidget(drive_cw_);
  drive_row->addWidget(drive_ccw_);
  robot_layout->addLayout(drive_row);
  robot_status_ = new QLabel;
  robot_status_->setWordWrap(true);
  robot_layout->addWidget(robot_status_);
  table_ = new QTableWidget(0, kColumnCount);
  table_->setObjectName(QStringLiteral("umbmarkRuns"));
  table_->setHorizontalHeaderLabels(
      {tr("Direction"), tr("Odometry x"), tr("Odometry y"), tr("Measured x"), tr("Measured y")});
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->verticalHeader()->setVisible(false);
  robot_layout->addWidget(table_);
  analyse_ = new QPushButton(tr("Analyse runs"));
  analyse_->setObjectName(QStringLiteral("umbmarkAnalyse"));
  robot_layout->addWidget(analyse_);
  pages_->addWidget(robot_page);

  // Results and writing the profile.
  paths_ = new UmbmarkPathView;
  right->addWidget(paths_, 1);
  report_ = new QPlainTextEdit;
  report_->setReadOnly(true);
  report_->setObjectName(QStringLiteral("umbmarkReport"));
  report_->setPlaceholderText(tr("Results appear here."));
  right->addWidget(report_, 1);
  auto* out_row = new QHBoxLayout;
  output_ = new QLineEdit(profile_file);
  output_->setToolTip(tr("The corrected profile is written here (atomically)."));
  write_ = new QPushButton(tr("Write profile"));
  write_->setObjectName(QStringLiteral("umbmarkWriteProfile"));
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

  connect(source_, &QComboBox::currentIndexChanged, this,
          [this](int index) { pages_->setCurrentIndex(index); });
  connect(run_sim_, &QPushButton::clicked, this, &UmbmarkWizard::runSimulation);
  connect(drive_cw_, &QPushButton::clicked, this, [this] {
    setBusy(true);
    emit driveSquareRequested(squareConfig(UmbmarkDirection::kClockwise));
  });
  connect(drive_ccw_, &QPushButton::clicked, this, [this] {
    setBusy(true);
    emit driveSquareRequested(squareConfig(UmbmarkDirection::kCounterClockwise));
  });
  connect(analyse_, &QPushButton::clicked, this, &UmbmarkWizard::analyseRobotRuns);
  connect(write_, &QPushButton::clicked, this, &UmbmarkWizard::writeProfile);
  resize(1000, 640);
}

void UmbmarkWizard::setSource(Source source) {
  source_->setCurrentIndex(static_cast<int>(source));
}

UmbmarkWizard::Source UmbmarkWizard::source() const {
  return static_cast<Source>(source_->currentIndex());
}

void UmbmarkWizard::setInjection(const UmbmarkInjection& injection) {
  inject_ed_->setValue(injection.wheel_diameter_ratio);
  inject_eb_->setValue(injection.wheelbase_scale);
  inject_slip_->setValue(injection.slip_stddev);
}

void UmbmarkWizard::setSide(double side_m) {
  side_->setValue(side_m);
}

void UmbmarkWizard::setRunsPerDirection(int runs) {
  runs_->setValue(runs);
}

void UmbmarkWizard::setSeed(int seed) {
  seed_->setValue(seed);
}

void UmbmarkWizard::setOutputFile(const QString& path) {
  output_->setText(path);
}

QString UmbmarkWizard::outputFile() const {
  return output_->text();
}

UmbmarkSquareConfig UmbmarkWizard::squareConfig(UmbmarkDirection direction) const {
  UmbmarkSquareConfig config;
  config.direction = direction;
  config.side_m = side_->value();
  return config;
}

void UmbmarkWizard::setBusy(bool busy) {
  drive_cw_->setEnabled(!busy);
  drive_ccw_->setEnabled(!busy);
  analyse_->setEnabled(!busy);
  run_sim_->setEnabled(!busy);
  source_->setEnabled(!busy);
  if (busy)
    robot_status_->setText(tr("Driving the square…"));
}

void UmbmarkWizard::runSimulation() {
  UmbmarkInjection injection;
  injection.wheel_diameter_ratio = inject_ed_->value();
  injection.wheelbase_scale = inject_eb_->value();
  injection.slip_stddev = inject_slip_->value();
  UmbmarkRunConfig config;
  config.side_m = side_->value();
  config.runs_per_direction = runs_->value();
  config.seed = static_cast<std::uint64_t>(seed_->value());
  QApplication::setOverrideCursor(Qt::WaitCursor);
  try {
    result_ = runUmbmarkProcedureInSimulator(profile_, injection, config, true);
    injected_ = injection;
  } catch (const std::exception& e) {
    result_.reset();
    injected_.reset();
    report_->setPlainText(tr("The simulation cannot run: %1").arg(QString::fromUtf8(e.what())));
  }
  QApplication::restoreOverrideCursor();
  if (result_)
    paths_->setTrials(result_->trials, result_->verification_trials, config.side_m);
  showResult();
}

void UmbmarkWizard::addRobotRun(UmbmarkDirection direction, const Vec2& odometry_end,
                                const std::optional<Vec2>& true_end) {
  setBusy(false);
  const int row = table_->rowCount();
  table_->insertRow(row);
  auto* dir = new QTableWidgetItem(QString::fromLatin1(toString(direction)));
  dir->setData(Qt::UserRole, static_cast<int>(direction));
  dir->setFlags(dir->flags() & ~Qt::ItemIsEditable);
  table_->setItem(row, kDirection, dir);
  for (int c : {kOdoX, kOdoY}) {
    auto* item = new QTableWidgetItem(number(c == kOdoX ? odometry_end.x() : odometry_end.y()));
    item->setFlags(item->flags() & ~Qt::ItemIsEditable);
    table_->setItem(row, c, item);
  }
  table_->setItem(row, kMeasX, new QTableWidgetItem(true_end ? number(true_end->x()) : QString()));
  table_->setItem(row, kMeasY, new QTableWidgetItem(true_end ? number(true_end->y()) : QString()));
  robot_status_->setText(
      true_end ? tr("Run %1 done; the measured end is the robot's reported "
                    "truth (overwrite it with your measurement).")
                     .arg(row + 1)
               : tr("Run %1 done: measure the end position and enter it.").arg(row + 1));
}

void UmbmarkWizard::robotRunFailed(const QString& reason) {
  setBusy(false);
  robot_status_->setText(tr("The square was not completed: %1").arg(reason));
}

int UmbmarkWizard::robotRunCount() const {
  return table_->rowCount();
}

QString UmbmarkWizard::robotStatusText() const {
  return robot_status_->text();
}

void UmbmarkWizard::analyseRobotRuns() {
  std::vector<UmbmarkRun> runs;
  QStringList problems;
  for (int row = 0; row < table_->rowCount(); ++row) {
    bool ok[4] = {false, false, false, false};
    const auto value = [&](int column, bool& good) {
      const QTableWidgetItem* item = table_->item(row, column);
      return item == nullptr ? 0.0 : item->text().trimmed().toDouble(&good);
    };
    const double ox = value(kOdoX, ok[0]), oy = value(kOdoY, ok[1]);
    const double mx = value(kMeasX, ok[2]), my = value(kMeasY, ok[3]);
    if (!(ok[0] && ok[1] && ok[2] && ok[3])) {
      problems << tr("run %1: the measured end is missing or not a number").arg(row + 1);
      continue;
    }
    UmbmarkRun run;
    run.direction =
        static_cast<UmbmarkDirection>(table_->item(row, kDirection)->data(Qt::UserRole).toInt());
    run.error_m = Vec2(mx - ox, my - oy);
    runs.push_back(run);
  }
  result_ = analyseMeasuredUmbmark(profile_, runs, side_->value());
  injected_.reset();
  paths_->clear();
  showResult();
  if (!problems.isEmpty())
    report_->appendPlainText(QStringLiteral("\n") + problems.join(QLatin1Char('\n')));
}

QString UmbmarkWizard::resultText() const {
  return report_->toPlainText();
}

void UmbmarkWizard::showResult() {
  write_->setEnabled(result_ && result_->ok);
  write_status_->clear();
  if (!result_)
    return;
  QStringList lines;
  const UmbmarkAnalysis& a = result_->analysis;
  if (!result_->ok) {
    lines << tr("The analysis failed:");
    for (const std::string& d : result_->diagnostics)
      lines << QString::fromStdString(d);
    report_->setPlainText(lines.join(QLatin1Char('\n')));
    return;
  }
  lines << tr("Runs: %1 clockwise, %2 counter-clockwise").arg(a.cw_runs).arg(a.ccw_runs);
  lines << tr("Centre of gravity cw: (%1, %2) m, ccw: (%3, %4) m")
               .arg(number(a.cg_cw.x(), 3), number(a.cg_cw.y(), 3), number(a.cg_ccw.x(), 3),
                    number(a.cg_ccw.y(), 3));
  lines << tr("E_max,syst: %1 m").arg(number(a.e_max_syst_m, 4));
  lines << tr("Wheel-diameter ratio E_d: %1").arg(number(a.wheel_diameter_ratio, 5));
  lines << tr("Wheelbase ratio E_b: %1").arg(number(a.wheelbase_ratio, 5));
  if (injected_) {
    const auto share = [](double recovered, double injected) {
      return injected == 1.0 ? 0.0 : std::abs(recovered - injected) / std::abs(injected - 1.0);
    };
    lines << tr("  recovered within %1 % (E_d) and %2 % (E_b) of the injected errors")
                 .arg(number(100.0 * share(a.wheel_diameter_ratio, injected_->wheel_diameter_ratio),
                             1),
                      number(100.0 * share(a.wheelbase_ratio, injected_->wheelbase_scale), 1));
  }
  lines << tr("Corrected wheelbase: %1 m (was %2 m)")
               .arg(number(result_->corrected.drive.wheelbase_m, 5),
                    number(profile_.drive.wheelbase_m, 5));
  const ProfileOdometry odo = profileOdometry(result_->corrected);
  lines << tr("Wheel scales: left %1, right %2")
               .arg(number(odo.odometry.left_wheel_scale, 5),
                    number(odo.odometry.right_wheel_scale, 5));
  if (result_->verification) {
    lines << tr("Verification on the corrected odometry: E_max,syst %1 m (x%2 better)")
                 .arg(number(result_->verification->e_max_syst_m, 4),
                      number(result_->improvement(), 1));
  }
  for (const std::string& d : result_->diagnostics)
    lines << QString::fromStdString(d);
  report_->setPlainText(lines.join(QLatin1Char('\n')));
}

bool UmbmarkWizard::writeProfile() {
  if (!result_ || !result_->ok)
    return false;
  const QString path = output_->text().trimmed();
  if (const auto error = saveCalibratedProfile(result_->corrected, path.toStdString())) {
    write_status_->setText(tr("Not written: %1").arg(QString::fromStdString(*error)));
    return false;
  }
  write_status_->setText(
      tr("Wrote %1. The corrections apply when the profile is next loaded.").arg(path));
  emit profileWritten(path);
  return true;
}

}  // namespace irgs::widgets
