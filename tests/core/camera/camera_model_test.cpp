#include <gtest/gtest.h>

#include <cmath>

#include "core/camera/camera_model.hpp"
#include "core/camera/ceiling_camera_config.hpp"
#include "core/camera/tilt_servo.hpp"
#include "core/robot/robot_profile_file.hpp"

namespace irgs {
namespace {

constexpr double kTol = 1e-9;

CeilingView upView(double tilt_deg) {
  return CeilingView(CameraIntrinsics{}, CameraMount{0.0, 0.0, 0.5}, 2.5, degToRad(tilt_deg));
}

TEST(CeilingView, LookingStraightUpThePointOverheadIsThePrincipalPoint) {
  const CeilingView view = upView(90.0);
  const auto p = view.project(Vec2(0.0, 0.0));
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->x(), 319.5, kTol);
  EXPECT_NEAR(p->y(), 239.5, kTol);
}

TEST(CeilingView, LookingUpForwardIsDownTheImageAndLeftIsLeft) {
  const CeilingView view = upView(90.0);
  const double f = CameraIntrinsics{}.fx_px;
  // h = 2 m above the camera: 1 m ahead is f / 2 pixels down, 1 m left is f / 2 pixels left.
  const auto ahead = view.project(Vec2(1.0, 0.0));
  const auto left = view.project(Vec2(0.0, 1.0));
  ASSERT_TRUE(ahead && left);
  EXPECT_NEAR(ahead->x(), 319.5, kTol);
  EXPECT_NEAR(ahead->y(), 239.5 + f / 2.0, kTol);
  EXPECT_NEAR(left->x(), 319.5 - f / 2.0, kTol);
  EXPECT_NEAR(left->y(), 239.5, kTol);
}

TEST(CeilingView, TheOpticalAxisMeetsTheCeilingAtHOverTanTheta) {
  for (double tilt_deg : {35.0, 45.0, 60.0, 85.0}) {
    const CeilingView view(CameraIntrinsics{}, CameraMount{0.1, 0.05, 0.4}, 2.6,
                           degToRad(tilt_deg));
    const Vec2 axis_hit(0.1 + 2.2 / std::tan(degToRad(tilt_deg)), 0.05);
    const auto p = view.project(axis_hit);
    ASSERT_TRUE(p) << tilt_deg;
    EXPECT_NEAR(p->x(), 319.5, 1e-6) << tilt_deg;
    EXPECT_NEAR(p->y(), 239.5, 1e-6) << tilt_deg;
  }
}

TEST(CeilingView, BackProjectionInvertsProjection) {
  const CeilingView view(CameraIntrinsics{}, CameraMount{0.1, -0.05, 0.45}, 2.7, degToRad(40.0));
  for (const Vec2& q : {Vec2(2.0, 0.3), Vec2(4.5, -1.2), Vec2(1.6, 0.9)}) {
    const auto px = view.project(q);
    ASSERT_TRUE(px);
    const auto back = view.backProject(*px);
    ASSERT_TRUE(back);
    EXPECT_NEAR((*back - q).norm(), 0.0, 1e-9);
  }
}

TEST(CeilingView, PointsBehindTheCameraDoNotProject) {
  const CeilingView view = upView(35.0);
  EXPECT_FALSE(view.project(Vec2(-40.0, 0.0)));
  // The image's bottom row at 35 deg looks 11.6 deg above the horizon: it still meets the
  // ceiling; a ray below the horizon does not.
  EXPECT_TRUE(view.backProject(Vec2(320.0, 479.0)));
  const CeilingView low(CameraIntrinsics{}, CameraMount{0.0, 0.0, 0.5}, 2.5, degToRad(10.0));
  EXPECT_FALSE(low.backProject(Vec2(320.0, 479.0)));
}

TEST(CeilingView, RejectsACeilingBelowTheCamera) {
  EXPECT_THROW(CeilingView(CameraIntrinsics{}, CameraMount{0.0, 0.0, 2.6}, 2.5, 1.0),
               std::invalid_argument);
}

TEST(TiltLaw, IsNinetyDegreesNearThirtyFiveFarAndLinearBetween) {
  const TiltLaw law{degToRad(35.0), degToRad(90.0), 0.5, 4.5};
  EXPECT_NEAR(radToDeg(law.tiltFor(0.0)), 90.0, kTol);
  EXPECT_NEAR(radToDeg(law.tiltFor(0.5)), 90.0, kTol);
  EXPECT_NEAR(radToDeg(law.tiltFor(2.5)), 62.5, kTol);
  EXPECT_NEAR(radToDeg(law.tiltFor(4.5)), 35.0, kTol);
  EXPECT_NEAR(radToDeg(law.tiltFor(20.0)), 35.0, kTol);
  EXPECT_NEAR(law.distanceFor(law.tiltFor(1.7)), 1.7, 1e-12);
  EXPECT_NEAR(radToDeg(tiltFromVertical(law.tiltFor(0.0))), 0.0, kTol);  // A002-5: beta = 0
  EXPECT_NEAR(radToDeg(tiltFromVertical(law.tiltFor(9.0))), 55.0, kTol);
}

TEST(TiltServo, MovesNoFasterThanItsRate) {
  TiltServo servo(degToRad(35.0), degToRad(90.0));
  EXPECT_NEAR(radToDeg(servo.step(degToRad(90.0), 0.1)), 44.0, 1e-9);
  EXPECT_NEAR(radToDeg(servo.step(degToRad(90.0), 1.0)), 90.0, 1e-9);
  EXPECT_NEAR(radToDeg(servo.step(degToRad(80.0), 1.0)), 80.0, 1e-9);
}

TEST(CeilingCameraConfig, ReadsEveryKey) {
  const auto json = nlohmann::json::parse(R"({
    "width_px": 320, "height_px": 240, "fx_px": 300, "fy_px": 301, "cx_px": 160, "cy_px": 120,
    "mount": {"x_m": 0.1, "y_m": 0.02, "z_m": 0.6},
    "tilt": {"min_deg": 40, "max_deg": 85, "near_m": 0.2, "far_m": 5, "rate_degps": 60},
    "working_range_m": 3.5, "ceiling_height_m": 2.8})");
  const auto r = ceilingCameraFromJson(json);
  ASSERT_TRUE(r.errors.empty()) << r.errors.front();
  EXPECT_EQ(r.config.intrinsics.width_px, 320);
  EXPECT_DOUBLE_EQ(r.config.intrinsics.fy_px, 301.0);
  EXPECT_DOUBLE_EQ(r.config.mount.z_m, 0.6);
  EXPECT_NEAR(radToDeg(r.config.tilt.min_tilt_rad), 40.0, 1e-12);
  EXPECT_NEAR(radToDeg(r.config.tilt_rate_radps), 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.config.working_range_m, 3.5);
  EXPECT_DOUBLE_EQ(r.config.ceilingHeight(2.5), 2.8);
  const auto again = ceilingCameraFromJson(ceilingCameraToJson(r.config));
  EXPECT_TRUE(again.errors.empty());
  EXPECT_DOUBLE_EQ(again.config.tilt.far_m, 5.0);
}

TEST(CeilingCameraConfig, ReportsBadValuesAndKeepsDefaults) {
  const auto r = ceilingCameraFromJson(
      nlohmann::json::parse(R"({"fx_px": -1, "tilt": {"near_m": 5, "far_m": 1}, "lens": 1})"));
  ASSERT_EQ(r.errors.size(), 3u);
  EXPECT_EQ(r.errors[0], "/ceiling_camera/fx_px: expected a number > 0");
  EXPECT_DOUBLE_EQ(r.config.intrinsics.fx_px, CameraIntrinsics{}.fx_px);
}

TEST(CeilingCameraConfig, LoadsFromARobotProfileWithoutWarnings) {
  const std::string text = R"({"name": "cam", "drive": {"wheel_radius_m": 0.05,
    "wheelbase_m": 0.4}, "body_outline": [[0.3,0.2],[-0.3,0.2],[-0.3,-0.2],[0.3,-0.2]],
    "ceiling_camera": {"mount": {"x_m": 0.2, "z_m": 0.7}}})";
  const RobotProfileResult loaded = parseRobotProfileJson(text, "cam.json");
  ASSERT_TRUE(loaded.profile);
  EXPECT_TRUE(loaded.diagnostics.empty());
  const auto cam = ceilingCameraFromProfile(*loaded.profile);
  EXPECT_TRUE(cam.errors.empty());
  EXPECT_DOUBLE_EQ(cam.config.mount.x_m, 0.2);
  EXPECT_DOUBLE_EQ(cam.config.mount.z_m, 0.7);
  EXPECT_EQ(cam.config.intrinsics.width_px, 640);
}

}  // namespace
}  // namespace irgs
