// The planning panel (setters silent, buttons follow the running task) and the canvas's
// planning modes (click to pick a goal, drag a region, Esc) with the overlay drawn.

#include "widgets/planning/planning_panel.hpp"

#include <gtest/gtest.h>

#include <QImage>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QtTest/QTest>

#include "widgets/canvas/map_canvas.hpp"

namespace irgs::widgets {
namespace {

QPushButton* button(const PlanningPanel& panel, const char* name) {
  return panel.findChild<QPushButton*>(QString::fromLatin1(name));
}

TEST(PlanningPanel, SettersDoNotEmitAndButtonsFollowTheRunningTask) {
  PlanningPanel panel;
  QSignalSpy source(&panel, &PlanningPanel::planSourceChanged);
  QSignalSpy pick(&panel, &PlanningPanel::pickGoalToggled);
  panel.setPlanSource(PlanSource::kSonarGrid);
  panel.setPickGoalChecked(true);
  panel.setLaneWidth(0.4);
  EXPECT_EQ(source.count(), 0);
  EXPECT_EQ(pick.count(), 0);
  EXPECT_EQ(panel.planSource(), PlanSource::kSonarGrid);
  EXPECT_DOUBLE_EQ(panel.laneWidth(), 0.4);

  EXPECT_FALSE(button(panel, "driveGoal")->isEnabled());  // nothing planned yet
  panel.setGoalDrivable(true);
  EXPECT_TRUE(button(panel, "driveGoal")->isEnabled());
  panel.setRunningTask(PlanningPanel::Task::kGoal);
  EXPECT_FALSE(button(panel, "driveGoal")->isEnabled());
  EXPECT_TRUE(button(panel, "stopGoal")->isEnabled());
  EXPECT_FALSE(button(panel, "mapBuildStart")->isEnabled());
  panel.setRunningTask(PlanningPanel::Task::kMapBuilding, true);
  EXPECT_EQ(button(panel, "mapBuildPause")->text(), QStringLiteral("Resume"));
  EXPECT_TRUE(button(panel, "mapBuildAbort")->isEnabled());
  panel.setRunningTask(PlanningPanel::Task::kNone);
  EXPECT_FALSE(button(panel, "saveBuiltMap")->isEnabled());
  panel.setBuiltMapAvailable(true);
  EXPECT_TRUE(button(panel, "saveBuiltMap")->isEnabled());
  panel.setPlanSource(PlanSource::kBuiltMap);
  EXPECT_EQ(panel.planSource(), PlanSource::kBuiltMap);
  panel.setBuiltMapAvailable(false);  // the built map went away: back to the loaded map
  EXPECT_EQ(panel.planSource(), PlanSource::kWorldMap);
}

TEST(PlanningPanel, ShowsPathStatsAndCoverage) {
  PlanningPanel panel;
  panel.setGoalPreview(PlanningPanel::PathStats{7, 5.123, 42.0},
                       PlanningPanel::PathStats{2, 5.2, 30.5}, QStringLiteral("note"));
  EXPECT_EQ(panel.findChild<QLabel*>(QStringLiteral("rawTurns"))->text(), QStringLiteral("7"));
  EXPECT_EQ(panel.findChild<QLabel*>(QStringLiteral("rawLength"))->text(),
            QStringLiteral("5.12 m"));
  EXPECT_EQ(panel.findChild<QLabel*>(QStringLiteral("amendedTime"))->text(),
            QStringLiteral("30.5 s"));
  panel.setGoalPreview(std::nullopt, std::nullopt, QString());
  EXPECT_EQ(panel.findChild<QLabel*>(QStringLiteral("rawTurns"))->text(), QStringLiteral("–"));
  auto* bar = panel.findChild<QProgressBar*>(QStringLiteral("coverageBar"));
  panel.setCoverage(0.834);
  EXPECT_EQ(bar->value(), 834);
  EXPECT_EQ(bar->format(), QStringLiteral("Swept: 83.4 %"));
  panel.setCoverage(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(bar->value(), 0);
}

TEST(PlanningPanel, UserActionsEmitTheirSignals) {
  PlanningPanel panel;
  QSignalSpy pick(&panel, &PlanningPanel::pickGoalToggled);
  QSignalSpy start(&panel, &PlanningPanel::mapBuildStartRequested);
  QTest::mouseClick(button(panel, "pickGoal"), Qt::LeftButton);
  ASSERT_EQ(pick.count(), 1);
  EXPECT_TRUE(pick.at(0).at(0).toBool());
  QTest::mouseClick(button(panel, "mapBuildStart"), Qt::LeftButton);
  EXPECT_EQ(start.count(), 1);
}

class CanvasModes : public ::testing::Test {
 protected:
  void SetUp() override {
    WorldMap map;
    map.walls.push_back({"outer", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, true, {}});
    canvas_.resize(400, 300);
    canvas_.setWorldMap(map);
    canvas_.setView(Vec2(2.0, 1.5), 100.0);
  }
  MapCanvas canvas_;
};

TEST_F(CanvasModes, APickGoalClickGivesTheWorldPointButADragPans) {
  QSignalSpy clicked(&canvas_, &MapCanvas::worldClicked);
  QTest::mouseClick(&canvas_, Qt::LeftButton, {}, QPoint(300, 100));
  EXPECT_EQ(clicked.count(), 0);  // navigation mode: no goals
  canvas_.setInteraction(MapCanvas::Interaction::kPickGoal);
  QTest::mouseClick(&canvas_, Qt::LeftButton, {}, QPoint(300, 100));
  ASSERT_EQ(clicked.count(), 1);
  EXPECT_NEAR(clicked.at(0).at(0).toDouble(), 3.0, 0.01);
  EXPECT_NEAR(clicked.at(0).at(1).toDouble(), 2.0, 0.01);
  // A drag of 40 px pans instead.
  const Vec2 before = canvas_.viewCentre();
  QTest::mousePress(&canvas_, Qt::LeftButton, {}, QPoint(200, 150));
  QTest::mouseMove(&canvas_, QPoint(240, 150));
  QTest::mouseRelease(&canvas_, Qt::LeftButton, {}, QPoint(240, 150));
  EXPECT_EQ(clicked.count(), 1);
  EXPECT_NEAR(canvas_.viewCentre().x(), before.x() - 0.4, 1e-9);
}

TEST_F(CanvasModes, ARegionDragGivesTheRectangleAndEscapeEndsTheMode) {
  QSignalSpy region(&canvas_, &MapCanvas::regionSelected);
  QSignalSpy mode(&canvas_, &MapCanvas::interactionChanged);
  canvas_.setInteraction(MapCanvas::Interaction::kSelectRegion);
  EXPECT_EQ(mode.count(), 1);
  QTest::mousePress(&canvas_, Qt::LeftButton, {}, QPoint(300, 250));
  QTest::mouseMove(&canvas_, QPoint(200, 150));
  QTest::mouseRelease(&canvas_, Qt::LeftButton, {}, QPoint(100, 50));
  ASSERT_EQ(region.count(), 1);
  EXPECT_NEAR(region.at(0).at(0).toDouble(), 1.0, 1e-9);  // x0 <= x1, y0 <= y1
  EXPECT_NEAR(region.at(0).at(1).toDouble(), 0.5, 1e-9);
  EXPECT_NEAR(region.at(0).at(2).toDouble(), 3.0, 1e-9);
  EXPECT_NEAR(region.at(0).at(3).toDouble(), 2.5, 1e-9);
  EXPECT_NEAR(canvas_.viewCentre().x(), 2.0, 1e-9);  // the drag did not pan
  // A tiny drag is not a region.
  QTest::mousePress(&canvas_, Qt::LeftButton, {}, QPoint(100, 100));
  QTest::mouseRelease(&canvas_, Qt::LeftButton, {}, QPoint(102, 101));
  EXPECT_EQ(region.count(), 1);
  QTest::keyClick(&canvas_, Qt::Key_Escape);
  EXPECT_EQ(canvas_.interaction(), MapCanvas::Interaction::kNavigate);
  EXPECT_EQ(mode.count(), 2);
}

TEST_F(CanvasModes, TheOverlayIsDrawnAndSkipsNonFinitePoints) {
  const QImage empty = canvas_.grab().toImage();
  PlanningOverlay overlay;
  overlay.raw_path = {Vec2(0.5, 0.5), Vec2(1.5, 0.5), Vec2(1.5, 2.5)};
  overlay.amended_path = {Vec2(0.5, 0.5), Vec2(1.5, 2.5)};
  overlay.goal = Vec2(1.5, 2.5);
  overlay.indices = {Vec2(3.0, 1.0), Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0)};
  Box2 box;
  box.extend(Vec2(2.5, 0.5));
  box.extend(Vec2(3.5, 1.5));
  overlay.region = box;
  canvas_.setPlanningOverlay(overlay);
  EXPECT_EQ(canvas_.planningOverlay().amended_path.size(), 2u);
  const QImage drawn = canvas_.grab().toImage();
  // The amended path's teal is on the diagonal's middle (1.0, 1.5) -> pixel (100, 150).
  const QColor mid = drawn.pixelColor(100, 150);
  EXPECT_NE(mid, empty.pixelColor(100, 150));
  EXPECT_GT(mid.green(), mid.red());
  canvas_.setPlanningOverlay({});
  EXPECT_TRUE(canvas_.planningOverlay().empty());
}

}  // namespace
}  // namespace irgs::widgets
