#include "app/gui/parameters_controller.hpp"

#include <QAction>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>
#include <limits>

#include "app/gui/link_controller.hpp"
#include "app/gui/localization_controller.hpp"
#include "app/gui/planning_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "app/robot/firmware_params.hpp"
#include "core/estimation/estimator_runner.hpp"
#include "widgets/params/parameter_table.hpp"

namespace irgs::gui {
namespace {

using widgets::ParameterSpec;

const QString kFirmwarePrefix = QStringLiteral("firmware/");

// The algorithm parameters: key, label, unit, range, default (from the code's own defaults),
// decimals, description.
std::vector<ParameterSpec> mappingSpecs(double default_resolution_m) {
  return {
      {QStringLiteral("mapping/grid_resolution_m"), QObject::tr("Grid resolution"),
       QStringLiteral("m"), 0.005, 0.5, default_resolution_m, default_resolution_m, 3, false,
       QObject::tr("Cell size of the session's sonar occupancy grid; a change starts an empty "
                   "grid")},
      {QStringLiteral("mapping/sonar_valid_distance_m"), QObject::tr("Sonar valid distance"),
       QStringLiteral("m"), 0.0, 10.0, 0.0, 0.0, 2, false,
       QObject::tr("Echoes farther than this are treated as no echo up to it (0: each sonar's "
                   "max range)")},
  };
}

std::vector<ParameterSpec> localizationSpecs() {
  const EkfLocalizerConfig ekf;
  const EstimatorRunnerConfig runner;
  return {
      {QStringLiteral("ekf/eps1_m"), QObject::tr("Gate ε1 (corner/edge match radius)"),
       QStringLiteral("m"), 0.0, 2.0, ekf.eps1_m, ekf.eps1_m, 3, false,
       QObject::tr("Paper 000, (41): a reading matches a corner/edge within this distance")},
      {QStringLiteral("ekf/eps2_deg"), QObject::tr("Gate ε2 (wall angle window)"),
       QStringLiteral("deg"), 0.0, 90.0, radToDeg(ekf.eps2_rad), radToDeg(ekf.eps2_rad), 2, false,
       QObject::tr("Paper 000, (42): a reading matches a wall within this angle")},
      {QStringLiteral("ekf/gate"), QObject::tr("Mahalanobis gate g"), QString(), 0.0, 1000.0, 0.0,
       0.0, 2, false,
       QObject::tr("Paper 000, (49): updates with v²/S above g are rejected. 0: no gate (the "
                   "paper's choice; 16 after an initial pose dragged by hand)")},
      {QStringLiteral("ekf/sigma_d_m"), QObject::tr("Range noise σd"), QStringLiteral("m"), 0.0001,
       1.0, std::sqrt(ekf.r_d_m2), std::sqrt(ekf.r_d_m2), 4, false,
       QObject::tr("Measurement noise of a stereo range (R_d = σd²)")},
      {QStringLiteral("ekf/sigma_theta_deg"), QObject::tr("Bearing noise σθ"),
       QStringLiteral("deg"), 0.01, 45.0, radToDeg(std::sqrt(ekf.r_theta_rad2)),
       radToDeg(std::sqrt(ekf.r_theta_rad2)), 2, false,
       QObject::tr("Measurement noise of a stereo bearing (R_θ = σθ²)")},
      {QStringLiteral("ekf/wheel_variance_per_m"), QObject::tr("Process noise (wheel variance)"),
       QStringLiteral("m²/m"), 0.0, 0.1, runner.process.wheel_variance_per_m,
       runner.process.wheel_variance_per_m, 6, false,
       QObject::tr("Variance of each wheel's travel per metre driven (prediction noise)")},
      {QStringLiteral("ekf/stereo_period_s"), QObject::tr("Stereo firing period"),
       QStringLiteral("s"), 0.01, 2.0, runner.stereo_period_s, runner.stereo_period_s, 3, false,
       QObject::tr("Each stereo sensor fires once per period (000: 40 ms)")},
      {QStringLiteral("ekf/caster_lambda"), QObject::tr("Caster process noise λ"), QString(), 0.0,
       100.0, runner.caster_lambda, runner.caster_lambda, 4, false,
       QObject::tr("Paper 000, (36): the three-caster EKF's process noise Q = λ‖e‖ I6 per 1 ms "
                   "period, e the least-squares residual of the six caster encoders (000: "
                   "0.005)")},
  };
}

std::vector<ParameterSpec> planningSpecs() {
  const PlanningSettings p;
  return {
      {QStringLiteral("planning/turn_quantum_deg"), QObject::tr("Turn quantum"),
       QStringLiteral("deg"), 0.0, 90.0, radToDeg(p.turn_quantum_rad), radToDeg(p.turn_quantum_rad),
       1, false, QObject::tr("Travel turns are multiples of this angle (0: exact turns)")},
      {QStringLiteral("planning/budget_s"), QObject::tr("A* time budget"), QStringLiteral("s"),
       0.01, 10.0, p.budget_s, p.budget_s, 2, false,
       QObject::tr("Wall time A* may search before it returns its best partial path")},
      {QStringLiteral("planning/max_expansions"), QObject::tr("A* expansion budget"),
       QStringLiteral("cells"), 0.0, 1e8, static_cast<double>(p.max_expansions),
       static_cast<double>(p.max_expansions), 0, false, QObject::tr("0: unlimited")},
      {QStringLiteral("planning/clearance_m"), QObject::tr("Clearance"), QStringLiteral("m"), 0.0,
       1.0, p.clearance_m, p.clearance_m, 3, false,
       QObject::tr("Kept between the robot's body and obstacles, beyond its radius")},
      {QStringLiteral("planning/resolution_m"), QObject::tr("Planning grid resolution"),
       QStringLiteral("m"), 0.01, 0.5, p.resolution_m, p.resolution_m, 3, false,
       QObject::tr("Cell size of the planners' grid")},
  };
}

ParameterSpec readOnly(const QString& key, const QString& label, const QString& unit, double value,
                       int decimals = 3) {
  ParameterSpec s;
  s.key = key;
  s.label = label;
  s.unit = unit;
  s.value = value;
  s.decimals = decimals;
  s.read_only = true;
  s.description = QObject::tr("From the robot profile file (read-only here)");
  return s;
}

}  // namespace

ParametersController::ParametersController(SessionController& session,
                                           LocalizationController& localization,
                                           PlanningController& planning, LinkController& link,
                                           QSettings& settings, QMainWindow& window)
    : QObject(&window),
      session_(session),
      localization_(localization),
      planning_(planning),
      link_(link),
      settings_(settings) {
  dock_ = new QDockWidget(tr("Parameters"), &window);
  dock_->setObjectName(QStringLiteral("parametersDock"));
  auto* body = new QWidget(dock_);
  auto* layout = new QVBoxLayout(body);
  layout->setContentsMargins(4, 4, 4, 4);
  auto* bar = new QHBoxLayout;
  read_button_ = new QPushButton(tr("Read Firmware Parameters"), body);
  read_button_->setToolTip(tr("Ask the linked robot for all its parameters (PARAM_REQUEST_LIST)"));
  auto* defaults = new QPushButton(tr("Restore Defaults"), body);
  defaults->setToolTip(tr("Set the algorithm parameters back to their defaults"));
  status_ = new QLabel(body);
  bar->addWidget(read_button_);
  bar->addWidget(defaults);
  bar->addWidget(status_, 1);
  layout->addLayout(bar);
  table_ = new widgets::ParameterTable(body);
  layout->addWidget(table_, 1);
  dock_->setWidget(body);
  window.addDockWidget(Qt::RightDockWidgetArea, dock_);
  dock_->hide();
  QAction* toggle = dock_->toggleViewAction();
  toggle->setText(tr("P&arameters"));
  toggle->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_A));
  if (auto* view = window.menuBar()->findChild<QMenu*>(QStringLiteral("viewMenu")))
    view->addAction(toggle);
  else
    window.addAction(toggle);

  confirm_ = [this](const QString& question) {
    return QMessageBox::question(dock_, tr("Write Firmware Parameter"), question) ==
           QMessageBox::Yes;
  };

  buildProfileSection();
  buildAlgorithmSections();
  table_->setSection(kFirmwareSection, {});

  connect(table_, &widgets::ParameterTable::valueEdited, this, &ParametersController::edit);
  connect(read_button_, &QPushButton::clicked, this, [this] { readFirmwareParameters(); });
  connect(defaults, &QPushButton::clicked, this, [this] {
    for (const QString& section : {kMappingSection, kLocalizationSection, kPlanningSection})
      table_->restoreDefaults(section);
  });
  connect(&link_, &LinkController::linkedChanged, this, &ParametersController::onLinkedChanged);
  connect(&session_, &SessionController::robotReplaced, this, [this] {
    // Another robot profile could have been loaded: its geometry is what the table shows.
    buildProfileSection();
  });
  poll_timer_ = new QTimer(this);
  poll_timer_->setInterval(kPollInterval_ms);
  connect(poll_timer_, &QTimer::timeout, this, &ParametersController::poll);
  onLinkedChanged(link_.linked());
}

ParametersController::~ParametersController() = default;

QString ParametersController::settingsGroup() const {
  QString name = QString::fromStdString(session_.profile().name);
  if (name.isEmpty())
    name = QStringLiteral("robot");
  name.replace(QLatin1Char('/'), QLatin1Char('_'));
  return QStringLiteral("parameters/%1/").arg(name);
}

QString ParametersController::statusText() const {
  return status_->text();
}

void ParametersController::buildProfileSection() {
  const RobotProfile& p = session_.profile();
  std::vector<ParameterSpec> specs;
  const QString k = QStringLiteral("profile/");
  specs.push_back(readOnly(k + "wheel_radius", tr("Wheel radius"), QStringLiteral("m"),
                           p.drive.wheel_radius_m, 4));
  specs.push_back(
      readOnly(k + "wheelbase", tr("Wheelbase"), QStringLiteral("m"), p.drive.wheelbase_m, 4));
  specs.push_back(readOnly(k + "ticks_per_rad", tr("Encoder ticks per wheel radian"),
                           QStringLiteral("ticks/rad"), p.drive.ticksPerWheelRad(), 1));
  specs.push_back(
      readOnly(k + "body_radius", tr("Body radius"), QStringLiteral("m"), p.bodyRadius(), 3));
  specs.push_back(
      readOnly(k + "max_speed", tr("Max speed"), QStringLiteral("m/s"), p.limits.max_speed_mps, 3));
  specs.push_back(readOnly(k + "max_turn_rate", tr("Max turn rate"), QStringLiteral("deg/s"),
                           radToDeg(p.limits.max_turn_rate_radps), 1));
  specs.push_back(readOnly(k + "max_accel", tr("Max acceleration"), QStringLiteral("m/s²"),
                           p.limits.max_accel_mps2, 2));
  for (std::size_t i = 0; i < p.sonars.size(); ++i) {
    const SonarSpec& s = p.sonars[i];
    const QString name = s.name.empty() ? tr("Sonar %1").arg(i) : QString::fromStdString(s.name);
    const QString sk = k + QStringLiteral("sonar%1/").arg(i);
    specs.push_back(readOnly(sk + "x", tr("%1 mount x").arg(name), QStringLiteral("m"), s.mount.x));
    specs.push_back(readOnly(sk + "y", tr("%1 mount y").arg(name), QStringLiteral("m"), s.mount.y));
    specs.push_back(readOnly(sk + "theta", tr("%1 mount θ").arg(name), QStringLiteral("deg"),
                             radToDeg(s.mount.theta), 1));
    specs.push_back(readOnly(sk + "range", tr("%1 max range").arg(name), QStringLiteral("m"),
                             s.max_range_m, 2));
    specs.push_back(readOnly(sk + "beam", tr("%1 beam width").arg(name), QStringLiteral("deg"),
                             radToDeg(s.beam_width_rad), 1));
  }
  table_->setSection(QStringLiteral("%1: %2").arg(kProfileSection, QString::fromStdString(p.name)),
                     specs);
  // Collapsed by default: it is long and read-only.
  for (int i = 0; i < table_->topLevelItemCount(); ++i) {
    if (table_->topLevelItem(i)->text(0).startsWith(kProfileSection))
      table_->topLevelItem(i)->setExpanded(false);
  }
}

void ParametersController::buildAlgorithmSections() {
  const std::vector<std::pair<QString, std::vector<ParameterSpec>>> sections = {
      {kMappingSection, mappingSpecs(session_.grid().resolution_m())},
      {kLocalizationSection, localizationSpecs()},
      {kPlanningSection, planningSpecs()},
  };
  const QString group = settingsGroup();
  for (auto [title, specs] : sections) {
    for (ParameterSpec& s : specs) {
      const QVariant saved = settings_.value(group + s.key);
      bool ok = false;
      const double v = saved.toDouble(&ok);
      if (saved.isValid() && ok && std::isfinite(v))
        s.value = std::clamp(v, s.min, s.max);
    }
    table_->setSection(title, specs);
  }
  applyMapping();
  applyLocalization();
  applyPlanning();
}

void ParametersController::edit(const QString& key, double value) {
  if (key.startsWith(kFirmwarePrefix)) {
    writeFirmwareParameter(key.mid(kFirmwarePrefix.size()), value, true);
    return;
  }
  applyAlgorithmParameter(key, value, true);
}

void ParametersController::applyAlgorithmParameter(const QString& key, double value, bool save) {
  const auto spec = table_->spec(key);
  if (!spec || spec->read_only)
    return;
  value = std::clamp(value, spec->min, spec->max);
  table_->setValue(key, value);
  if (save)
    settings_.setValue(settingsGroup() + key, value);
  if (key.startsWith(QStringLiteral("mapping/")))
    applyMapping();
  else if (key.startsWith(QStringLiteral("ekf/")))
    applyLocalization();
  else if (key.startsWith(QStringLiteral("planning/")))
    applyPlanning();
  status_->setText(tr("%1 = %2 %3 applied").arg(spec->label).arg(value).arg(spec->unit));
}

void ParametersController::applyMapping() {
  const double resolution =
      table_->value(QStringLiteral("mapping/grid_resolution_m")).value_or(0.01);
  const double valid =
      table_->value(QStringLiteral("mapping/sonar_valid_distance_m")).value_or(0.0);
  try {
    session_.setMappingParameters(resolution,
                                  valid > 0.0 ? std::optional<double>(valid) : std::nullopt);
  } catch (const std::invalid_argument& e) {
    session_.report(EventLevel::kError, tr("Mapping parameters rejected: %1").arg(e.what()));
  }
}

void ParametersController::applyLocalization() {
  auto get = [this](const char* key) {
    return table_->value(QString::fromLatin1(key)).value_or(0.0);
  };
  const double eps1 = get("ekf/eps1_m");
  const double eps2 = degToRad(get("ekf/eps2_deg"));
  const double gate = get("ekf/gate");
  const double sigma_d = get("ekf/sigma_d_m");
  const double sigma_theta = degToRad(get("ekf/sigma_theta_deg"));
  const double wheel = get("ekf/wheel_variance_per_m");
  const double period = get("ekf/stereo_period_s");
  const double lambda = get("ekf/caster_lambda");
  localization_.setConfigAdjuster([=](EstimatorRunnerConfig& c) {
    c.ekf.eps1_m = eps1;
    c.ekf.eps2_rad = eps2;
    if (gate > 0.0)
      c.ekf.gate = gate;
    c.ekf.r_d_m2 = sigma_d * sigma_d;
    c.ekf.r_theta_rad2 = sigma_theta * sigma_theta;
    c.process.wheel_variance_per_m = wheel;
    c.stereo_period_s = period;
    c.caster_lambda = lambda;
  });
}

void ParametersController::applyPlanning() {
  auto get = [this](const char* key) {
    return table_->value(QString::fromLatin1(key)).value_or(0.0);
  };
  PlanningSettings s = planning_.settings();
  s.turn_quantum_rad = degToRad(get("planning/turn_quantum_deg"));
  s.budget_s = get("planning/budget_s");
  s.max_expansions = static_cast<std::uint64_t>(std::llround(get("planning/max_expansions")));
  s.clearance_m = get("planning/clearance_m");
  s.resolution_m = get("planning/resolution_m");
  planning_.setSettings(s);
}

bool ParametersController::readFirmwareParameters() {
  comms::FirmwareParameters* params = link_.firmwareParameters();
  if (params == nullptr) {
    status_->setText(tr("No robot linked: firmware parameters need a link"));
    return false;
  }
  params->requestParams();
  reading_ = true;
  status_->setText(tr("Reading firmware parameters…"));
  return true;
}

bool ParametersController::writeFirmwareParameter(const QString& name, double value, bool ask) {
  comms::FirmwareParameters* params = link_.firmwareParameters();
  const QString key = kFirmwarePrefix + name;
  const auto spec = table_->spec(key);
  if (params == nullptr) {
    status_->setText(tr("No robot linked: %1 not written").arg(name));
    return false;
  }
  const QString question =
      tr("Write %1 = %2 %3 to the robot?").arg(name).arg(value).arg(spec ? spec->unit : QString());
  // The value shown stays the robot's until it confirms the write.
  const auto current = params->firmwareParams();
  auto restore = [&] {
    for (const comms::ParamEntry& e : current) {
      if (QString::fromStdString(e.name) == name)
        table_->setValue(key, e.value);
    }
  };
  if (ask && (!confirm_ || !confirm_(question))) {
    restore();
    status_->setText(tr("%1 not written").arg(name));
    return false;
  }
  try {
    params->setParam(name.toStdString(), value);
  } catch (const std::invalid_argument& e) {
    restore();
    status_->setText(QString::fromUtf8(e.what()));
    return false;
  }
  table_->setStatus(key, tr("writing…"));
  status_->setText(tr("Writing %1…").arg(name));
  return true;
}

void ParametersController::poll() {
  comms::FirmwareParameters* params = link_.firmwareParameters();
  if (params == nullptr)
    return;
  for (const comms::ParamWriteResult& r : params->takeParamResults()) {
    const QString name = QString::fromStdString(r.name);
    const QString key = kFirmwarePrefix + name;
    const QString what = QString::fromLatin1(comms::toString(r.status));
    table_->setStatus(key, what);
    if (r.status == comms::ParamWriteStatus::kAccepted) {
      status_->setText(tr("%1 = %2 written").arg(name).arg(*r.applied));
      session_.report(EventLevel::kInfo,
                      tr("Firmware parameter %1 = %2 written").arg(name).arg(*r.applied));
    } else {
      const QString detail = r.applied
                                 ? tr("%1 %2: the robot kept %3").arg(name, what).arg(*r.applied)
                                 : tr("%1 %2: no answer from the robot").arg(name, what);
      status_->setText(detail);
      session_.report(EventLevel::kWarning, tr("Firmware parameter %1").arg(detail));
    }
  }
  refreshFirmwareSection();
  if (reading_ && !params->readingParams()) {
    reading_ = false;
    const std::vector<comms::ParamEntry> entries = params->firmwareParams();
    const int got = static_cast<int>(entries.size());
    const int expected = params->firmwareParamCount();
    status_->setText(expected > 0 && got >= expected
                         ? tr("%1 firmware parameters read").arg(got)
                         : tr("Firmware parameters: %1 of %2 read (no answer for the rest)")
                               .arg(got)
                               .arg(expected));
    QStringList values;
    for (const comms::ParamEntry& e : entries)
      values << QStringLiteral("%1=%2").arg(QString::fromStdString(e.name)).arg(e.value);
    session_.report(got > 0 && got >= expected ? EventLevel::kInfo : EventLevel::kWarning,
                    tr("Firmware parameters read (%1 of %2): %3")
                        .arg(got)
                        .arg(expected)
                        .arg(values.join(QLatin1Char(' '))));
  }
}

void ParametersController::refreshFirmwareSection() {
  const comms::FirmwareParameters* firmware = link_.firmwareParameters();
  if (firmware == nullptr)
    return;
  const std::vector<comms::ParamEntry> params = firmware->firmwareParams();
  if (static_cast<int>(params.size()) != shown_firmware_count_) {
    std::vector<ParameterSpec> specs;
    for (const comms::ParamEntry& e : params) {
      ParameterSpec s;
      s.key = kFirmwarePrefix + QString::fromStdString(e.name);
      s.label = QString::fromStdString(e.name);
      s.value = e.value;
      s.decimals = 3;
      s.min = -1e9;
      s.max = 1e9;
      if (const auto id = app::findParam(e.name)) {
        const app::ParamSpec& known = app::paramSpecs()[static_cast<std::size_t>(*id)];
        s.unit = QString::fromUtf8(known.unit.data(), static_cast<qsizetype>(known.unit.size()));
        s.min = known.min;
        s.max = known.max;
        s.description = QString::fromUtf8(known.description.data(),
                                          static_cast<qsizetype>(known.description.size()));
      }
      specs.push_back(s);
    }
    table_->setSection(kFirmwareSection, specs);
    shown_firmware_count_ = static_cast<int>(params.size());
    return;
  }
  for (const comms::ParamEntry& e : params) {
    const QString key = kFirmwarePrefix + QString::fromStdString(e.name);
    // Not while the user is typing a new value into it.
    if (QWidget* editor = table_->editor(key); editor != nullptr && editor->hasFocus())
      continue;
    table_->setValue(key, e.value);
  }
}

void ParametersController::onLinkedChanged(bool linked) {
  read_button_->setEnabled(linked);
  if (linked) {
    poll_timer_->start();
  } else {
    poll_timer_->stop();
    shown_firmware_count_ = -1;
    table_->setSection(kFirmwareSection, {});
  }
}

}  // namespace irgs::gui
