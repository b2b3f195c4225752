#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "core/camera/ceiling_renderer.hpp"
#include "core/vision/ceiling_vision.hpp"
#include "core/vision/image_convert.hpp"
#include "core/vision/vision_ceiling_observer.hpp"

namespace irgs::vision {
namespace {

CeilingView view(double tilt_deg) {
  return CeilingView(CameraIntrinsics{}, CameraMount{0.1, 0.0, 0.5}, 2.6, degToRad(tilt_deg));
}

TEST(TopViewGeometry, PixelsAndBodyPointsAreInverseAndMetric) {
  const TopViewGeometry g(view(60.0), TopViewConfig{});
  ASSERT_FALSE(g.empty());
  const Vec2 body(2.0, -0.4);
  const Vec2 px = g.bodyToPixel(body);
  EXPECT_NEAR((g.pixelToBody(px) - body).norm(), 0.0, 1e-12);
  // 1 m forward is 100 px up the top view.
  EXPECT_NEAR((g.bodyToPixel(body + Vec2(1.0, 0.0)) - px - Vec2(0.0, -100.0)).norm(), 0.0, 1e-9);
  EXPECT_LE(g.xFarM(), 6.0 + 1e-9);
}

TEST(TopViewGeometry, TheWarpMapsEachTopViewPixelToItsFramePixel) {
  const CeilingView v = view(45.0);
  const TopViewGeometry g(v, TopViewConfig{});
  const Vec2 body(2.5, 0.3);
  const Vec2 top = g.bodyToPixel(body);
  const Eigen::Vector3d q = g.frameFromTopView() * Eigen::Vector3d(top.x(), top.y(), 1.0);
  const auto expected = v.project(body);
  ASSERT_TRUE(expected);
  EXPECT_NEAR(q.x() / q.z(), expected->x(), 1e-6);
  EXPECT_NEAR(q.y() / q.z(), expected->y(), 1e-6);
}

TEST(MarkerDetector, FindsARenderedMarkerWhereItIs) {
  for (double tilt : {45.0, 70.0, 90.0}) {
    const CeilingView v = view(tilt);
    const TopViewGeometry g(v, TopViewConfig{});
    const Vec2 centre(0.5 * (g.xNearM() + std::min(g.xFarM(), 3.0)), 0.2);
    CeilingScene scene;
    scene.ceiling_height_m = 2.6;
    scene.markers.push_back({centre, 0.4, 0.2, 0.2});
    const RgbImage frame = renderCeiling(v, scene, Pose2{}, RenderSettings{});
    const CeilingVisionResult r = CeilingVision().process(frame, v);
    ASSERT_EQ(r.markers.markers.size(), 1u) << tilt;
    EXPECT_LT((r.markers.markers[0].centre_body_m - centre).norm(), 0.02) << tilt;
    EXPECT_GT(r.markers.markers[0].score, 0.8) << tilt;
    ASSERT_TRUE(r.markers.markers[0].heading_rad);
    EXPECT_NEAR(std::remainder(*r.markers.markers[0].heading_rad - 0.4, 0.5 * kPi), 0.0, 0.1);
  }
}

TEST(MarkerDetector, RejectsRedThingsOfTheWrongShapeOrSize) {
  const CeilingView v = view(90.0);
  CeilingScene scene;
  scene.ceiling_height_m = 2.6;
  scene.decorations.push_back({{Vec2(0.5, 0.4), 0.0, 0.45, 0.14}, {0.85, 0.12, 0.12}});  // sign
  scene.decorations.push_back({{Vec2(0.3, -0.5), 0.3, 0.4, 0.4}, kMarkerRed});           // too big
  scene.decorations.push_back({{Vec2(-0.2, 0.0), 0.0, 0.2, 0.2}, {0.9, 0.82, 0.2}});     // yellow
  const RgbImage frame = renderCeiling(v, scene, Pose2{}, RenderSettings{});
  const CeilingVisionResult r = CeilingVision().process(frame, v);
  EXPECT_TRUE(r.markers.markers.empty());
  int wrong_size = 0;
  for (const auto& c : r.markers.candidates)
    wrong_size += c.verdict == CandidateVerdict::kWrongSize;
  EXPECT_EQ(wrong_size, 2);
}

TEST(LightDetector, FindsTubesAndPanelsFarthestFirstWithTheirAxes) {
  const CeilingView v = view(60.0);
  CeilingScene scene;
  scene.ceiling_height_m = 2.6;
  // At 60 deg the camera sees the ceiling from 0.34 m to 2.93 m ahead.
  scene.lights.push_back({Vec2(1.2, 0.0), 0.0, 1.2, 0.1});   // tube along the corridor
  scene.lights.push_back({Vec2(2.3, -0.5), 0.0, 0.5, 0.5});  // panel, farther
  const RgbImage frame = renderCeiling(v, scene, Pose2{}, RenderSettings{});
  const CeilingVisionResult r = CeilingVision().process(frame, v);
  ASSERT_EQ(r.lights.size(), 2u);
  EXPECT_LT((r.lights[0].light.centre_body_m - Vec2(2.3, -0.5)).norm(), 0.05);
  EXPECT_LT((r.lights[1].light.centre_body_m - Vec2(1.2, 0.0)).norm(), 0.05);
  EXPECT_NEAR(std::remainder(r.lights[1].light.axis_rad, kPi), 0.0, 0.05);
  EXPECT_NEAR(r.lights[1].light.length_m, 1.2, 0.1);
}

TEST(VisionConfig, ReadsKeysAndReportsBadOnes) {
  const auto r = visionConfigFromJson(nlohmann::json::parse(
      R"({"marker": {"cr_threshold": 150, "min_score": 0.5}, "light": {"erode_px": 2.5},
          "top_view": {"px_per_m": 80}, "colour": 1})"));
  EXPECT_EQ(r.config.marker.cr_threshold, 150);
  EXPECT_DOUBLE_EQ(r.config.marker.min_score, 0.5);
  EXPECT_DOUBLE_EQ(r.config.top_view.px_per_m, 80.0);
  ASSERT_EQ(r.errors.size(), 2u);
  EXPECT_EQ(r.errors[0], "/light/erode_px: expected an integer");
  EXPECT_EQ(r.errors[1], "/colour: unknown key");
  const auto huge =
      visionConfigFromJson(nlohmann::json::parse(R"({"top_view": {"px_per_m": 1000}})"));
  ASSERT_EQ(huge.errors.size(), 1u);
  EXPECT_NE(huge.errors[0].find("above 16 Mpx"), std::string::npos);
  const auto again = visionConfigFromJson(visionConfigToJson(r.config));
  EXPECT_TRUE(again.errors.empty());
  EXPECT_EQ(again.config.marker.cr_threshold, 150);
}

TEST(ImageConvert, RoundTripsAndSwapsBgr) {
  RgbImage img(3, 2, {10, 20, 30});
  img.set(2, 1, {200, 100, 50});
  EXPECT_EQ(fromRgbMat(asRgbMat(img)), img);
  cv::Mat bgr;
  cv::cvtColor(asRgbMat(img), bgr, cv::COLOR_RGB2BGR);
  EXPECT_EQ(fromBgrMat(bgr), img);
}

TEST(VisionCeilingObserver, RendersThenDetectsInTheBodyFrameRepeatably) {
  const Pose2 robot{2.0, 1.0, 0.3};
  const Vec2 light_world = robot.toWorld(Vec2(2.6, -0.5));  // 55 deg sees 0.5 m .. 3.5 m ahead
  CeilingScene scene;
  scene.ceiling_height_m = 2.6;
  scene.markers.push_back({Vec2(4.0, 2.0), 0.0, 0.2, 0.2});
  scene.lights.push_back({light_world, 0.3, 1.0, 0.1});
  CeilingCameraConfig camera;
  camera.mount = {0.1, 0.0, 0.5};
  VisionCeilingObserver a(scene, camera), b(scene, camera);
  const CeilingObservation oa = a.observe(robot, degToRad(55.0), 1.5);
  const CeilingObservation ob = b.observe(robot, degToRad(55.0), 1.5);
  ASSERT_EQ(oa.markers.size(), 1u);
  EXPECT_LT((oa.markers[0].centre_body_m - robot.toBody(Vec2(4.0, 2.0))).norm(), 0.03);
  ASSERT_GE(oa.lights.size(), 1u);
  EXPECT_LT((oa.lights[0].centre_body_m - robot.toBody(light_world)).norm(), 0.05);
  EXPECT_DOUBLE_EQ(oa.time_s, 1.5);
  EXPECT_NEAR(oa.tilt_rad, degToRad(55.0), 1e-12);
  EXPECT_EQ(oa.markers[0].centre_body_m, ob.markers[0].centre_body_m);
  EXPECT_EQ(a.lastFrame(), b.lastFrame());
  EXPECT_EQ(a.framesRendered(), 1u);
  ASSERT_TRUE(a.lastResult());
  EXPECT_FALSE(a.lastResult()->top_view.empty());
}

}  // namespace
}  // namespace irgs::vision
