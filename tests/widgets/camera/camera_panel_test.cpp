#include "widgets/camera/camera_panel.hpp"

#include <gtest/gtest.h>

#include <QCheckBox>
#include <QImage>
#include <QSignalSpy>
#include <QSpinBox>

namespace irgs::widgets {
namespace {

CameraPanelFrame aFrame() {
  CameraPanelFrame f;
  f.frame = RgbImage(64, 48, {120, 120, 115});
  for (int y = 10; y < 20; ++y)
    for (int x = 30; x < 40; ++x)
      f.frame.set(x, y, {250, 40, 60});
  f.frame_overlay.markers.push_back({Vec2(30, 10), Vec2(39, 10), Vec2(39, 19), Vec2(30, 19)});
  f.top_view = RgbImage(40, 30, {100, 100, 100});
  f.top_overlay.lights.push_back({Vec2(5, 5), Vec2(20, 5), Vec2(20, 8), Vec2(5, 8)});
  f.top_overlay.target = Vec2(12, 6);
  f.time_s = 3.25;
  f.tilt_deg = 62.5;
  f.markers = 1;
  f.lights = 1;
  f.source = "simulated";
  return f;
}

TEST(CameraPanel, ShowsBothImagesAndSaysWhatWasDetected) {
  CameraPanel panel;
  panel.resize(640, 300);
  EXPECT_FALSE(panel.frameView().hasImage());
  panel.showFrame(aFrame());
  EXPECT_TRUE(panel.frameView().hasImage());
  EXPECT_TRUE(panel.topView().hasImage());
  EXPECT_TRUE(panel.statusText().contains("1 marker"));
  EXPECT_TRUE(panel.statusText().contains("62.5"));
  // The marker is drawn where the frame shows it: the accepted quadrilateral is green.
  const QImage shot = panel.frameView().grab().toImage();
  bool green = false;
  for (int y = 0; y < shot.height() && !green; ++y)
    for (int x = 0; x < shot.width() && !green; ++x) {
      const QColor c = shot.pixelColor(x, y);
      green = c.green() > 180 && c.red() < 90 && c.blue() < 120;
    }
  EXPECT_TRUE(green);
}

TEST(CameraPanel, AMessageClearsTheImages) {
  CameraPanel panel;
  panel.showFrame(aFrame());
  panel.showMessage(QStringLiteral("no ceiling"));
  EXPECT_FALSE(panel.frameView().hasImage());
  EXPECT_EQ(panel.statusText(), QStringLiteral("no ceiling"));
}

TEST(CameraPanel, TheTiltControlSwitchesBetweenAutomaticAndFixed) {
  CameraPanel panel;
  QSignalSpy spy(&panel, &CameraPanel::tiltModeChanged);
  EXPECT_TRUE(panel.autoTilt());
  panel.setFixedTiltDeg(45.0);
  EXPECT_FALSE(panel.autoTilt());
  EXPECT_DOUBLE_EQ(panel.fixedTiltDeg(), 45.0);
  ASSERT_GE(spy.count(), 1);
  EXPECT_FALSE(spy.last().at(0).toBool());
  EXPECT_DOUBLE_EQ(spy.last().at(1).toDouble(), 45.0);
  // A frame at another tilt does not move a fixed setting.
  panel.showFrame(aFrame());
  EXPECT_DOUBLE_EQ(panel.fixedTiltDeg(), 45.0);
}

TEST(CameraPanel, ToQImageCopiesPixels) {
  RgbImage img(2, 1, {1, 2, 3});
  img.set(1, 0, {200, 100, 50});
  const QImage q = toQImage(img);
  ASSERT_EQ(q.width(), 2);
  EXPECT_EQ(q.pixelColor(1, 0), QColor(200, 100, 50));
  EXPECT_TRUE(toQImage(RgbImage{}).isNull());
}

}  // namespace
}  // namespace irgs::widgets
