#include <gtest/gtest.h>

#include "core/camera/ceiling_renderer.hpp"

namespace irgs {
namespace {

CeilingScene oneOfEach() {
  CeilingScene scene;
  scene.ceiling_height_m = 2.5;
  scene.markers.push_back({Vec2(2.0, 1.0), 0.3, 0.2, 0.2});
  scene.lights.push_back({Vec2(2.0, 0.0), 0.0, 1.2, 0.1});
  return scene;
}

const Pose2 kRobot{1.5, 1.0, 0.0};

CeilingView view90() {
  return CeilingView(CameraIntrinsics{}, CameraMount{0.0, 0.0, 0.5}, 2.5, degToRad(90.0));
}

TEST(CeilingRenderer, SameSeedSameBytesOtherSeedOtherNoise) {
  RenderSettings s;
  s.seed = 7;
  const RgbImage a = renderCeiling(view90(), oneOfEach(), kRobot, s);
  const RgbImage b = renderCeiling(view90(), oneOfEach(), kRobot, s);
  s.seed = 8;
  const RgbImage c = renderCeiling(view90(), oneOfEach(), kRobot, s);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(a.width, 640);
  EXPECT_EQ(a.height, 480);
}

TEST(CeilingRenderer, MarkerIsRedLightSaturatedCeilingGrey) {
  RenderSettings s;
  s.noise_sigma = 0.0;
  const CeilingView view = view90();
  const RgbImage img = renderCeiling(view, oneOfEach(), kRobot, s);
  // Marker centre (2, 1) world = (0.5, 0) body; light centre (2, 0) world = (0.5, -1) body.
  const auto marker_px = view.project(kRobot.toBody(Vec2(2.0, 1.0)));
  const auto light_px = view.project(kRobot.toBody(Vec2(2.0, 0.0)));
  const auto plain_px = view.project(Vec2(-0.5, 0.7));
  ASSERT_TRUE(marker_px && light_px && plain_px);
  ASSERT_TRUE(view.inImage(*marker_px) && view.inImage(*light_px) && view.inImage(*plain_px));
  const auto at = [&](const Vec2& p) {
    return img.at(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  };
  const Rgb8 m = at(*marker_px), l = at(*light_px), c = at(*plain_px);
  EXPECT_GT(m.r, 200);
  EXPECT_LT(m.g, 60);
  EXPECT_EQ(l.r, 255);
  EXPECT_EQ(l.g, 255);
  EXPECT_NEAR(c.r, 0.62 * 255 * 1.0, 40);
  EXPECT_NEAR(c.r, c.g, 10);
}

TEST(CeilingRenderer, ExposureScalesTheCeiling) {
  RenderSettings s;
  s.noise_sigma = 0.0;
  s.exposure = 0.7;
  const RgbImage dim = renderCeiling(view90(), oneOfEach(), kRobot, s);
  s.exposure = 1.1;
  const RgbImage bright = renderCeiling(view90(), oneOfEach(), kRobot, s);
  const auto plain = view90().project(Vec2(-0.5, 0.7));
  const int x = static_cast<int>(plain->x()), y = static_cast<int>(plain->y());
  EXPECT_NEAR(bright.at(x, y).g / static_cast<double>(dim.at(x, y).g), 1.1 / 0.7, 0.05);
}

TEST(CeilingRenderer, ARayBelowTheHorizonSeesTheWall) {
  RenderSettings s;
  s.noise_sigma = 0.0;
  s.blur_sigma_px = 0.0;
  const CeilingView low(CameraIntrinsics{}, CameraMount{0.0, 0.0, 0.5}, 2.5, degToRad(10.0));
  const RgbImage img = renderCeiling(low, oneOfEach(), kRobot, s);
  EXPECT_LT(img.at(320, 479).r, 90);
}

}  // namespace
}  // namespace irgs
