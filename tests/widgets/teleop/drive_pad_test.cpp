#include "widgets/teleop/drive_pad.hpp"

#include <gtest/gtest.h>

#include <QSignalSpy>
#include <QtTest/QTest>

namespace irgs::widgets {
namespace {

class DrivePadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    pad.resize(200, 200);
    pad.setMaxSpeeds(0.4, 1.2);
    pad.show();
  }
  QPoint centre() const { return QPoint(100, 100); }
  std::pair<double, double> last(const QSignalSpy& spy) const {
    const QList<QVariant> args = spy.last();
    return {args.at(0).toDouble(), args.at(1).toDouble()};
  }
  DrivePad pad;
};

TEST_F(DrivePadTest, DraggingUpDrivesForwardAndReleaseStops) {
  QSignalSpy commands(&pad, &DrivePad::commandChanged);
  QSignalSpy released(&pad, &DrivePad::released);
  QTest::mousePress(&pad, Qt::LeftButton, {}, centre());
  EXPECT_TRUE(pad.dragging());
  EXPECT_EQ(commands.count(), 0);  // the centre is in the deadband: no command yet
  QTest::mouseMove(&pad, centre() + QPoint(0, -150));  // beyond the rim: full forward
  ASSERT_GE(commands.count(), 1);
  auto [v, w] = last(commands);
  EXPECT_NEAR(v, 0.4, 1e-9);
  EXPECT_NEAR(w, 0.0, 1e-9);
  EXPECT_NEAR(pad.knob().y(), -1.0, 1e-9);  // the knob stays on the rim
  QTest::mouseRelease(&pad, Qt::LeftButton, {}, centre() + QPoint(0, -150));
  EXPECT_EQ(released.count(), 1);
  EXPECT_FALSE(pad.dragging());
  EXPECT_EQ(pad.knob(), QPointF());
}

TEST_F(DrivePadTest, RightTurnsClockwiseAndHalfDeflectionIsSlowerThanHalfSpeed) {
  QSignalSpy commands(&pad, &DrivePad::commandChanged);
  QTest::mousePress(&pad, Qt::LeftButton, {}, centre());
  QTest::mouseMove(&pad, centre() + QPoint(200, 0));
  auto [v, w] = last(commands);
  EXPECT_NEAR(v, 0.0, 1e-9);
  EXPECT_NEAR(w, -1.2, 1e-9);
  QTest::mouseMove(&pad, centre() + QPoint(-43, 0));  // about half the radius to the left
  std::tie(v, w) = last(commands);
  EXPECT_GT(w, 0.0);        // left: counter-clockwise
  EXPECT_LT(w, 0.5 * 1.2);  // expo: finer near the centre
  QTest::mouseRelease(&pad, Qt::LeftButton, {}, centre());
}

TEST_F(DrivePadTest, HidingOrDisablingThePadWhileDraggingStops) {
  QSignalSpy released(&pad, &DrivePad::released);
  QTest::mousePress(&pad, Qt::LeftButton, {}, centre());
  QTest::mouseMove(&pad, centre() + QPoint(0, -60));
  pad.setEnabled(false);
  EXPECT_EQ(released.count(), 1);
  EXPECT_FALSE(pad.dragging());
  pad.setEnabled(true);
  QTest::mousePress(&pad, Qt::LeftButton, {}, centre());
  pad.hide();
  EXPECT_EQ(released.count(), 2);
}

}  // namespace
}  // namespace irgs::widgets
