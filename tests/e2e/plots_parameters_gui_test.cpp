// The plots and parameters docks in the main window, offscreen, with the simulated robot:
// telemetry and estimator fields reach the field browser and a panel plots them; algorithm
// parameters edited in the table take effect in the running session and are restored for the
// same robot in a new window.

#include <gtest/gtest.h>

#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QImage>
#include <QMenu>
#include <QMenuBar>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>
#include <cmath>
#include <numbers>

#include "app/gui/export_actions.hpp"
#include "app/gui/localization_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/parameters_controller.hpp"
#include "app/gui/planning_controller.hpp"
#include "app/gui/plots_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/params/parameter_table.hpp"
#include "widgets/plots/field_browser.hpp"
#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plot_panel.hpp"
#include "widgets/plots/plots_dock.hpp"

namespace irgs::gui {
namespace {

class DocksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    ASSERT_TRUE(dir_.isValid());
    settings_ = std::make_unique<QSettings>(dir_.filePath(QStringLiteral("settings.ini")),
                                            QSettings::IniFormat);
    openWindow();
  }
  void openWindow() {
    window_.reset();
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    window_ = std::make_unique<MainWindow>(*session_, *settings_);
    session_->loadWorld(test::squareRoom(), QStringLiteral("room.json"));
    window_->resize(1200, 800);
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
  }
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds / 0.02 + 0.5); ++i)
      session_->tick(0.02);
  }

  QTemporaryDir dir_;
  std::unique_ptr<QSettings> settings_;
  std::unique_ptr<SessionController> session_;
  std::unique_ptr<MainWindow> window_;
};

TEST_F(DocksTest, TelemetryAndEstimatorFieldsArePlottedFromTheSession) {
  PlotsController& plots = window_->plots();
  EXPECT_FALSE(plots.dock().isVisible());
  plots.dock().toggleViewAction()->trigger();
  EXPECT_TRUE(plots.dock().isVisible());
  window_->localization().setEstimator(EstimatorKind::kStereoEkf);
  session_->drive(0.2, 0.3);
  run(3.0);
  const widgets::PlotDataHub& hub = plots.hub();
  for (const char* key : {"Telemetry/Odometry pose/x", "Telemetry/True pose (simulator)/theta",
                          "Telemetry/Velocity/linear", "Command/Velocity/angular",
                          "Estimator/Estimate/x", "Estimator/Error/position"}) {
    ASSERT_TRUE(hub.contains(QString::fromLatin1(key))) << key;
  }
  const widgets::PlotSeries* x = hub.series(QStringLiteral("Telemetry/Odometry pose/x"));
  EXPECT_GT(x->size(), 100u);  // one per tick (and more at speed)
  EXPECT_NEAR(x->newest().value, session_->latestSample()->odometry_pose.x, 1e-9);
  EXPECT_NE(plots.plots().browser().itemFor(QStringLiteral("Estimator/Error/position")), nullptr);
  widgets::PlotsDock& dock = plots.plots();
  dock.setCurrentPanel(&dock.panel(0));
  dock.plotFields({QStringLiteral("Telemetry/Velocity/linear")});
  dock.refreshNow();
  const auto v = dock.panel(0).visibleRange(QStringLiteral("Telemetry/Velocity/linear"));
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR(v->max, 0.2, 0.02);
}

TEST_F(DocksTest, AlgorithmParametersTakeEffectAndAreSavedPerRobot) {
  ParametersController& params = window_->parameters();
  widgets::ParameterTable& table = params.table();
  // Grid resolution: the session's grid starts over at the new cell size.
  ASSERT_TRUE(table.value(QStringLiteral("mapping/grid_resolution_m")).has_value());
  QDoubleSpinBox* box = table.editor(QStringLiteral("mapping/grid_resolution_m"));
  ASSERT_NE(box, nullptr);
  box->setValue(0.05);
  emit box->editingFinished();  // what Enter / focus-out does
  EXPECT_DOUBLE_EQ(session_->grid().resolution_m(), 0.05);
  params.edit(QStringLiteral("mapping/sonar_valid_distance_m"), 1.5);
  EXPECT_EQ(session_->sonarValidDistance_m(), std::optional<double>(1.5));
  // The EKF's gates restart the running estimator with them.
  window_->localization().setEstimator(EstimatorKind::kStereoEkf);
  params.edit(QStringLiteral("ekf/eps1_m"), 0.2);
  params.edit(QStringLiteral("ekf/gate"), 9.0);
  ASSERT_NE(window_->localization().runner(), nullptr);
  EXPECT_DOUBLE_EQ(window_->localization().runner()->config().ekf.eps1_m, 0.2);
  EXPECT_DOUBLE_EQ(window_->localization().runner()->config().ekf.gate, 9.0);
  // The three-caster EKF's adaptive process-noise scale lambda (paper 000, (36)).
  EXPECT_DOUBLE_EQ(*table.value(QStringLiteral("ekf/caster_lambda")), 0.005);
  params.edit(QStringLiteral("ekf/caster_lambda"), 0.05);
  EXPECT_DOUBLE_EQ(window_->localization().runner()->config().caster_lambda, 0.05);
  // Planning: the turn quantum and the A* budget.
  params.edit(QStringLiteral("planning/turn_quantum_deg"), 45.0);
  params.edit(QStringLiteral("planning/budget_s"), 1.0);
  EXPECT_NEAR(window_->planning().settings().turn_quantum_rad, std::numbers::pi / 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(window_->planning().settings().budget_s, 1.0);
  // Out of range is clamped to the range.
  params.edit(QStringLiteral("planning/turn_quantum_deg"), 500.0);
  EXPECT_DOUBLE_EQ(*table.value(QStringLiteral("planning/turn_quantum_deg")), 90.0);
  // Read-only profile values are shown.
  EXPECT_TRUE(table.spec(QStringLiteral("profile/wheelbase"))->read_only);
  EXPECT_DOUBLE_EQ(*table.value(QStringLiteral("profile/wheelbase")),
                   session_->profile().drive.wheelbase_m);
  // No link: firmware parameters cannot be read.
  EXPECT_FALSE(params.readFirmwareParameters());

  // A new window for the same robot applies the saved values.
  openWindow();
  EXPECT_DOUBLE_EQ(session_->grid().resolution_m(), 0.05);
  EXPECT_EQ(session_->sonarValidDistance_m(), std::optional<double>(1.5));
  EXPECT_NEAR(window_->planning().settings().turn_quantum_rad, std::numbers::pi / 2.0, 1e-12);
  window_->localization().setEstimator(EstimatorKind::kStereoEkf);
  EXPECT_DOUBLE_EQ(window_->localization().runner()->config().ekf.eps1_m, 0.2);
  // Restore Defaults puts them back.
  window_->parameters().table().restoreDefaults(ParametersController::kMappingSection);
  EXPECT_DOUBLE_EQ(session_->grid().resolution_m(),
                   *window_->parameters()
                        .table()
                        .spec(QStringLiteral("mapping/grid_resolution_m"))
                        ->default_value);
}

TEST_F(DocksTest, ExportsTheMapViewTheSonarGridAndASummaryMidSession) {
  auto* file = window_->menuBar()->findChild<QMenu*>(QStringLiteral("fileMenu"));
  ASSERT_NE(file, nullptr);
  bool found = false;
  for (QAction* a : file->actions())
    found = found || a->menu() == &window_->exports().menu();
  EXPECT_TRUE(found) << "File > Export is missing";
  session_->drive(0.2, 0.4);
  run(4.0);
  session_->report(EventLevel::kWarning, QStringLiteral("a <test> warning"));
  ExportActions& exports = window_->exports();
  QTemporaryDir out;
  ASSERT_TRUE(out.isValid());

  const QString png = out.filePath(QStringLiteral("map.png"));
  ASSERT_EQ(exports.exportMapPng(png), QString());
  EXPECT_EQ(QImage(png).size(), window_->canvas().size());

  const QString svg = out.filePath(QStringLiteral("map.svg"));
  ASSERT_EQ(exports.exportMapSvg(svg), QString());
  QFile svg_file(svg);
  ASSERT_TRUE(svg_file.open(QIODevice::ReadOnly));
  const QByteArray svg_text = svg_file.readAll();
  EXPECT_TRUE(svg_text.contains("<svg"));
  EXPECT_TRUE(svg_text.contains("<path") || svg_text.contains("<polyline"));  // vector walls

  const QString yaml = out.filePath(QStringLiteral("sonar.yaml"));
  ASSERT_EQ(exports.exportRosMap(yaml), QString());
  QFile yaml_file(yaml);
  ASSERT_TRUE(yaml_file.open(QIODevice::ReadOnly | QIODevice::Text));
  const QString yaml_text = QString::fromUtf8(yaml_file.readAll());
  EXPECT_TRUE(yaml_text.contains(QStringLiteral("image: sonar.pgm"))) << yaml_text.toStdString();
  EXPECT_TRUE(QFile::exists(out.filePath(QStringLiteral("sonar.pgm"))));

  const recording::SessionSummary summary = exports.liveSummary();
  EXPECT_NEAR(summary.duration_s, session_->displayTime_s(), 1e-9);
  // 4 s at up to 0.2 m/s (the robot accelerates first).
  EXPECT_GT(summary.distance_m, 0.4);
  EXPECT_LT(summary.distance_m, 0.81);
  EXPECT_FALSE(summary.link.has_value());  // the simulator
  const QString md = out.filePath(QStringLiteral("summary.md"));
  ASSERT_EQ(exports.exportSummary(md), QString());
  QFile md_file(md);
  ASSERT_TRUE(md_file.open(QIODevice::ReadOnly | QIODevice::Text));
  const QString md_text = QString::fromUtf8(md_file.readAll());
  EXPECT_TRUE(md_text.contains(QStringLiteral("| warning | a <test> warning |")))
      << md_text.toStdString();
  EXPECT_TRUE(md_text.contains(QStringLiteral("| Distance | ")));
  const QString html = out.filePath(QStringLiteral("summary.html"));
  ASSERT_EQ(exports.exportSummary(html), QString());
  EXPECT_NE(exports.exportSummary(out.filePath(QStringLiteral("summary.txt"))), QString());
}

}  // namespace
}  // namespace irgs::gui
