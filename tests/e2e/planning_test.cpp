// The planning modes of the window offscreen, on the bundled default map: click a goal, see the
// raw A* path beside the amended one, drive it; drag a region and cover it; start, pause, abort
// map building and save the built map.

#include <gtest/gtest.h>

#include <QFileInfo>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QSplitter>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>
#include <functional>
#include <set>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/planning_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/mission/map_building_mission.hpp"
#include "core/world/map_file.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/planning/planning_panel.hpp"

namespace irgs::gui {
namespace {

WorldMap defaultMap() {
  MapLoadResult loaded = loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/default.json");
  if (!loaded.map)
    throw std::runtime_error("bundled default.json does not load");
  return *loaded.map;
}

class PlanningTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    ASSERT_TRUE(dir_.isValid());
    settings_ = std::make_unique<QSettings>(dir_.filePath(QStringLiteral("settings.ini")),
                                            QSettings::IniFormat);
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    window_ = std::make_unique<MainWindow>(*session_, *settings_);
    connect();
    session_->loadWorld(defaultMap(), QStringLiteral("default.json"));
    window_->restoreSettings(QSize(1280, 820));
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
    window_->controlTabs().setCurrentWidget(&window_->planningPanel());
    window_->canvas().zoomToFit();
  }

  void connect() {
    QObject::connect(session_.get(), &SessionController::consoleEvent,
                     [this](EventLevel, double, const QString& text) { console_ << text; });
  }

  // Runs the session at full simulator speed until done() or max_s of robot time.
  void runUntil(const std::function<bool()>& done, double max_s) {
    session_->setSpeedFactor(0.0);
    const double until = session_->robotTime_s() + max_s;
    while (!done() && session_->robotTime_s() < until)
      session_->tick(0.02);
  }

  QPushButton* button(const char* name) const {
    auto* b = window_->planningPanel().findChild<QPushButton*>(QString::fromLatin1(name));
    EXPECT_NE(b, nullptr) << name;
    return b;
  }

  QPoint widgetPoint(const Vec2& world) const {
    return window_->canvas().worldToWidget(world).toPoint();
  }

  bool consoleHas(const QString& part) const {
    return std::any_of(console_.begin(), console_.end(),
                       [&](const QString& line) { return line.contains(part); });
  }

  QTemporaryDir dir_;
  std::unique_ptr<QSettings> settings_;
  std::unique_ptr<SessionController> session_;
  std::unique_ptr<MainWindow> window_;
  QStringList console_;
};

TEST_F(PlanningTest, AGoalClickPreviewsFewerAmendedTurnsThenDrivesToTheGoal) {
  widgets::MapCanvas& canvas = window_->canvas();
  QTest::mouseClick(button("pickGoal"), Qt::LeftButton);
  ASSERT_EQ(canvas.interaction(), widgets::MapCanvas::Interaction::kPickGoal);

  const Vec2 goal(5.6, 3.2);  // the bedroom: through the study and the east doorway
  QTest::mouseClick(&canvas, Qt::LeftButton, {}, widgetPoint(goal));
  const auto& preview = window_->planning().goalPreview();
  ASSERT_TRUE(preview.has_value());
  ASSERT_TRUE(preview->ok) << preview->error;
  EXPECT_LT((preview->goal - goal).norm(), 0.05);
  EXPECT_LT(preview->amended_turns, preview->raw_turns);
  EXPECT_LE(preview->amended_time_s, preview->raw_time_s);
  // The panel and the canvas show both paths.
  auto* amended_turns = window_->planningPanel().findChild<QLabel*>(QStringLiteral("amendedTurns"));
  ASSERT_NE(amended_turns, nullptr);
  EXPECT_EQ(amended_turns->text(), QString::number(preview->amended_turns));
  EXPECT_EQ(canvas.planningOverlay().raw_path, preview->raw);
  EXPECT_EQ(canvas.planningOverlay().amended_path, preview->amended);
  EXPECT_TRUE(consoleHas(QStringLiteral("amended")));

  ASSERT_TRUE(button("driveGoal")->isEnabled());
  QTest::mouseClick(button("driveGoal"), Qt::LeftButton);
  ASSERT_TRUE(window_->planning().behaviours().running());
  EXPECT_TRUE(button("stopGoal")->isEnabled());
  EXPECT_FALSE(button("driveGoal")->isEnabled());
  runUntil([&] { return !window_->planning().behaviours().running(); }, 240.0);

  const BehaviourStatus status = window_->planning().behaviours().status();
  EXPECT_TRUE(status.finished);
  EXPECT_FALSE(status.failed) << status.message;
  ASSERT_TRUE(session_->latestSample()->true_pose.has_value());
  EXPECT_LT((session_->latestSample()->true_pose->position() - goal).norm(), 0.15);
  EXPECT_TRUE(consoleHas(QStringLiteral("arrived at turning point 1/")));
  EXPECT_TRUE(consoleHas(QStringLiteral("arrived at the goal")));
  EXPECT_TRUE(button("driveGoal")->isEnabled());
}

TEST_F(PlanningTest, AGoalOnAnObstacleIsRefusedWithAReason) {
  window_->planning().planGoal(Vec2(7.0, 4.9));  // the middle of the bed
  const auto& preview = window_->planning().goalPreview();
  ASSERT_TRUE(preview.has_value());
  EXPECT_FALSE(preview->ok);
  EXPECT_NE(preview->error.find("obstacle"), std::string::npos) << preview->error;
  EXPECT_FALSE(button("driveGoal")->isEnabled());
  EXPECT_TRUE(window_->planning().goalPreview()->amended.empty());
}

TEST_F(PlanningTest, EscapeLeavesThePickGoalModeAndUnchecksTheButton) {
  QTest::mouseClick(button("pickGoal"), Qt::LeftButton);
  ASSERT_TRUE(button("pickGoal")->isChecked());
  QTest::keyClick(&window_->canvas(), Qt::Key_Escape);
  EXPECT_EQ(window_->canvas().interaction(), widgets::MapCanvas::Interaction::kNavigate);
  EXPECT_FALSE(button("pickGoal")->isChecked());
}

TEST_F(PlanningTest, CoverageOfADraggedRegionSweepsAtLeast80Percent) {
  widgets::MapCanvas& canvas = window_->canvas();
  window_->planningPanel().setCurrentTab(widgets::PlanningPanel::Tab::kCoverage);
  QTest::mouseClick(button("selectRegion"), Qt::LeftButton);
  ASSERT_EQ(canvas.interaction(), widgets::MapCanvas::Interaction::kSelectRegion);
  // 1.4 m x 1.3 m of the living room around the start (3.0, 1.6).
  QTest::mousePress(&canvas, Qt::LeftButton, {}, widgetPoint(Vec2(2.5, 1.2)));
  QTest::mouseMove(&canvas, widgetPoint(Vec2(3.2, 2.0)));
  QTest::mouseRelease(&canvas, Qt::LeftButton, {}, widgetPoint(Vec2(3.9, 2.5)));
  const auto& preview = window_->planning().coveragePreview();
  ASSERT_TRUE(preview.has_value());
  ASSERT_TRUE(preview->ok) << preview->error;
  EXPECT_GT(preview->coverage.coverage, 0.9);
  EXPECT_TRUE(canvas.planningOverlay().region.has_value());
  EXPECT_EQ(canvas.planningOverlay().coverage_path, preview->path);

  QTest::mouseClick(button("driveCoverage"), Qt::LeftButton);
  ASSERT_TRUE(window_->planning().behaviours().running());
  runUntil([&] { return !window_->planning().behaviours().running(); }, 600.0);
  EXPECT_FALSE(window_->planning().behaviours().status().failed)
      << window_->planning().behaviours().status().message;
  ASSERT_TRUE(window_->planning().coverage().has_value());
  EXPECT_GE(*window_->planning().coverage(), 0.8);
  auto* bar = window_->planningPanel().findChild<QProgressBar*>(QStringLiteral("coverageBar"));
  ASSERT_NE(bar, nullptr);
  EXPECT_GE(bar->value(), 800);
  EXPECT_TRUE(consoleHas(QStringLiteral("of the region")));
}

TEST_F(PlanningTest, MapBuildingStartsChangesPhasePausesAndSavesTheBuiltMap) {
  window_->planningPanel().setCurrentTab(widgets::PlanningPanel::Tab::kMapBuilding);
  std::set<std::string> phases;
  QObject::connect(&window_->planning().behaviours(), &BehaviourController::statusChanged,
                   [&](const BehaviourStatus& status) { phases.insert(status.phase); });
  QTest::mouseClick(button("mapBuildStart"), Qt::LeftButton);
  ASSERT_TRUE(window_->planning().behaviours().running());
  ASSERT_NE(window_->planning().mapBuilding(), nullptr);
  runUntil([&] { return phases.size() >= 2; }, 120.0);
  EXPECT_GE(phases.size(), 2u);
  auto* phase = window_->planningPanel().findChild<QLabel*>(QStringLiteral("mapBuildPhase"));
  ASSERT_NE(phase, nullptr);
  EXPECT_TRUE(phase->text().startsWith(QStringLiteral("Phase: ")));

  // Pause: the robot comes to rest and the behaviour holds.
  QTest::mouseClick(button("mapBuildPause"), Qt::LeftButton);
  EXPECT_TRUE(window_->planning().behaviours().paused());
  EXPECT_EQ(button("mapBuildPause")->text(), QStringLiteral("Resume"));
  runUntil([] { return false; }, 2.0);
  EXPECT_LT(std::abs(session_->latestSample()->measured_velocity.linear_mps), 1e-3);
  EXPECT_TRUE(window_->planning().behaviours().running());
  QTest::mouseClick(button("mapBuildPause"), Qt::LeftButton);
  EXPECT_FALSE(window_->planning().behaviours().paused());
  runUntil([] { return false; }, 20.0);

  QTest::mouseClick(button("mapBuildAbort"), Qt::LeftButton);
  EXPECT_FALSE(window_->planning().behaviours().running());
  ASSERT_TRUE(window_->planning().builtGrid().has_value());
  EXPECT_TRUE(button("saveBuiltMap")->isEnabled());
  const QString yaml = dir_.filePath(QStringLiteral("built.yaml"));
  const auto error = window_->planning().saveBuiltMap(yaml);
  EXPECT_FALSE(error.has_value()) << error->toStdString();
  EXPECT_TRUE(QFileInfo(yaml).isFile());
  EXPECT_TRUE(QFileInfo(dir_.filePath(QStringLiteral("built.pgm"))).isFile());
}

TEST_F(PlanningTest, SavingWithoutABuiltMapExplainsWhy) {
  const auto error = window_->planning().saveBuiltMap(dir_.filePath(QStringLiteral("x.yaml")));
  ASSERT_TRUE(error.has_value());
  EXPECT_TRUE(error->contains(QStringLiteral("map building")));
  EXPECT_FALSE(button("saveBuiltMap")->isEnabled());
}

TEST_F(PlanningTest, PlanningOnAnEmptySonarGridSaysSo) {
  window_->planningPanel().setPlanSource(widgets::PlanSource::kSonarGrid);
  session_->resetGrid();
  EXPECT_FALSE(window_->planning().planGoal(Vec2(3.5, 2.0)));
  ASSERT_TRUE(window_->planning().goalPreview().has_value());
  EXPECT_NE(window_->planning().goalPreview()->error.find("sonar grid is empty"), std::string::npos)
      << window_->planning().goalPreview()->error;
  EXPECT_FALSE(button("driveGoal")->isEnabled());
}

}  // namespace
}  // namespace irgs::gui
