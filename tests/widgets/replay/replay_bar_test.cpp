// The replay bar (issue 6 item 3): speeds x0.25..x16, play/pause and step requests, seeking by
// clicking the timeline, event marks, the position text.

#include "widgets/replay/replay_bar.hpp"

#include <gtest/gtest.h>

#include <QComboBox>
#include <QSignalSpy>
#include <QTest>
#include <QToolButton>

namespace irgs::widgets {
namespace {

TEST(ReplayBar, OffersSpeedsFromAQuarterToSixteen) {
  ReplayBar bar;
  EXPECT_EQ(bar.speedBox().count(), 7);
  EXPECT_EQ(ReplayBar::speeds().front(), 0.25);
  EXPECT_EQ(ReplayBar::speeds().back(), 16.0);
  bar.setSpeed(3.0);  // the nearest offered speed on a log scale: x4
  EXPECT_EQ(bar.speedBox().currentData().toDouble(), 4.0);
  QSignalSpy chosen(&bar, &ReplayBar::speedChosen);
  bar.speedBox().setCurrentIndex(0);
  ASSERT_EQ(chosen.count(), 1);
  EXPECT_EQ(chosen.at(0).at(0).toDouble(), 0.25);
}

TEST(ReplayBar, ThePlayButtonAsksForTheOtherStateAndStepAsksForAStep) {
  ReplayBar bar;
  QSignalSpy toggled(&bar, &ReplayBar::playToggled);
  QSignalSpy step(&bar, &ReplayBar::stepRequested);
  bar.playButton().click();
  ASSERT_EQ(toggled.count(), 1);
  EXPECT_TRUE(toggled.at(0).at(0).toBool());
  bar.setPlaying(true);
  bar.playButton().click();
  EXPECT_FALSE(toggled.at(1).at(0).toBool());
  bar.stepButton().click();
  EXPECT_EQ(step.count(), 1);
}

TEST(ReplayBar, ClickingTheTimelineSeeksToTheTimeUnderTheMouse) {
  ReplayBar bar;
  bar.resize(800, 40);
  bar.setDuration(100.0);
  bar.show();
  ReplayTimeline& timeline = bar.timeline();
  QSignalSpy seek(&bar, &ReplayBar::seekRequested);
  const int x = timeline.width() / 2;
  QTest::mouseClick(&timeline, Qt::LeftButton, {}, QPoint(x, timeline.height() / 2));
  ASSERT_EQ(seek.count(), 1);
  EXPECT_NEAR(seek.at(0).at(0).toDouble(), timeline.timeAt(x), 1e-9);
  EXPECT_NEAR(seek.at(0).at(0).toDouble(), 50.0, 2.0);
  EXPECT_EQ(timeline.timeAt(-100), 0.0);
  EXPECT_EQ(timeline.timeAt(10000), 100.0);
}

TEST(ReplayBar, ShowsThePositionAndKeepsItOnTheTimeline) {
  ReplayBar bar;
  bar.setDuration(75.5);
  bar.setPosition(61.25);
  EXPECT_EQ(bar.positionText(), QStringLiteral("1:01.2 / 1:15.5"));
  bar.setPosition(500.0);
  EXPECT_EQ(bar.timeline().position_s(), 75.5);
  bar.setMarks({{10.0, ReplayMarkKind::kError, QStringLiteral("CRC errors")}});
  EXPECT_EQ(bar.timeline().marks().size(), 1u);
}

}  // namespace
}  // namespace irgs::widgets
