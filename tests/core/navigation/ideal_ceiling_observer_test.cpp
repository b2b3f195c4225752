#include "core/navigation/ideal_ceiling_observer.hpp"

#include <gtest/gtest.h>

namespace irgs {
namespace {

WorldMap oneMarkerOneLight() {
  WorldMap map;
  map.ceiling_height_m = 2.6;  // 2.0 m above a camera at 0.6 m
  map.markers.push_back({"M", Vec2(3.0, 0.0), 0.0, 0.2, {}});
  map.lights.push_back({"L", Segment{Vec2(5.0, -0.6), Vec2(5.0, 0.6)}, 0.1, {}});
  return map;
}

IdealCameraParams noiseless() {
  IdealCameraParams p;
  p.position_stddev_m = 0.0;
  p.position_stddev_per_m = 0.0;
  return p;
}

TEST(IdealCeilingObserver, SeesAMarkerAheadAtThirtyFiveDegreesButNotLookingStraightUp) {
  IdealCeilingObserver cam(oneMarkerOneLight(), noiseless(), 1);
  const Pose2 pose{0.0, 0.0, 0.0};
  const CeilingObservation far = cam.observe(pose, degToRad(35.0), 0.0);
  ASSERT_EQ(far.markers.size(), 1u);
  EXPECT_NEAR(far.markers[0].centre_body_m.x(), 3.0, 1e-12);
  EXPECT_NEAR(far.markers[0].centre_body_m.y(), 0.0, 1e-12);
  EXPECT_TRUE(cam.observe(pose, degToRad(90.0), 0.0).markers.empty());
  // Overhead it is seen looking straight up, not looking ahead.
  const Pose2 under{3.0, 0.0, 0.0};
  EXPECT_EQ(cam.observe(under, degToRad(90.0), 0.0).markers.size(), 1u);
  EXPECT_TRUE(cam.observe(under, degToRad(35.0), 0.0).markers.empty());
}

TEST(IdealCeilingObserver, ReportsPositionsInTheBodyFrameAndNothingBehind) {
  IdealCeilingObserver cam(oneMarkerOneLight(), noiseless(), 1);
  // Facing +y from (3, -2): the marker is 2 m ahead.
  const CeilingObservation obs = cam.observe({3.0, -2.0, kPi / 2}, degToRad(45.0), 0.0);
  ASSERT_EQ(obs.markers.size(), 1u);
  EXPECT_NEAR(obs.markers[0].centre_body_m.x(), 2.0, 1e-12);
  EXPECT_NEAR(obs.markers[0].centre_body_m.y(), 0.0, 1e-12);
  EXPECT_TRUE(cam.observe({3.0, -2.0, -kPi / 2}, degToRad(35.0), 0.0).markers.empty());
}

TEST(IdealCeilingObserver, ALightAcrossTheViewHasItsCentreAndAxis) {
  IdealCeilingObserver cam(oneMarkerOneLight(), noiseless(), 1);
  const CeilingObservation obs = cam.observe({0.0, 0.0, 0.0}, degToRad(35.0), 0.0);
  ASSERT_EQ(obs.lights.size(), 1u);
  EXPECT_NEAR(obs.lights[0].centre_body_m.x(), 5.0, 1e-9);
  EXPECT_NEAR(std::abs(obs.lights[0].axis_rad), kPi / 2, 1e-9);  // across the travel direction
  EXPECT_NEAR(obs.lights[0].length_m, 1.2, 1e-9);
}

TEST(IdealCeilingObserver, NoiseIsSeeded) {
  IdealCameraParams p;
  p.position_stddev_m = 0.02;
  IdealCeilingObserver a(oneMarkerOneLight(), p, 7), b(oneMarkerOneLight(), p, 7),
      c(oneMarkerOneLight(), p, 8);
  const auto ma = a.observe({}, degToRad(35.0), 0.0).markers.at(0).centre_body_m;
  const auto mb = b.observe({}, degToRad(35.0), 0.0).markers.at(0).centre_body_m;
  const auto mc = c.observe({}, degToRad(35.0), 0.0).markers.at(0).centre_body_m;
  EXPECT_EQ(ma, mb);
  EXPECT_NE(ma, mc);
  EXPECT_NEAR(ma.x(), 3.0, 0.2);
}

}  // namespace
}  // namespace irgs
