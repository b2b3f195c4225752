// The issue-7 acceptance measurements on small sets (the full tables are produced by
// irgs-vision-eval, docs/landmark-navigation.md): the top view is metric at every tilt of the
// servo's range, and the marker detector finds the marker where it is.

#include <gtest/gtest.h>

#include "core/vision/vision_evaluation.hpp"

namespace irgs::vision {
namespace {

class AtTilt : public ::testing::TestWithParam<double> {};

TEST_P(AtTilt, TheTopViewOfARenderedGridIsMetricToAFewMillimetres) {
  const TopViewErrorRow row = topViewGridError(CeilingCameraConfig{}, VisionConfig{},
                                               degToRad(GetParam()), degToRad(1.0), 3);
  ASSERT_GE(row.exact.expected, 8);
  EXPECT_GE(row.exact.count, row.exact.expected * 9 / 10);
  EXPECT_LT(row.exact.mean_m, 0.006);
  EXPECT_LT(row.exact.max_m, 0.03);
  // A 1 deg tilt error moves the grid: the measurement can tell a wrong transform.
  EXPECT_GT(row.tilt_off.mean_m, 2.0 * row.exact.mean_m);
}

TEST_P(AtTilt, TheMarkerDetectorFindsMarkersToACentimetre) {
  const ErrorStats s =
      markerCentreError(CeilingCameraConfig{}, VisionConfig{}, degToRad(GetParam()), 8, 11);
  ASSERT_GE(s.expected, 6);
  EXPECT_GE(s.count, s.expected - 1);
  EXPECT_LT(s.mean_m, 0.01);
  EXPECT_LT(s.max_m, 0.03);
}

INSTANTIATE_TEST_SUITE_P(Tilts, AtTilt, ::testing::Values(35.0, 45.0, 60.0, 85.0, 90.0));

TEST(VisionDetection, RecallAndPrecisionHoldOnASmallGeneratedSet) {
  const DetectionStats d = evaluateDetection(CeilingCameraConfig{}, VisionConfig{}, 40, 5);
  ASSERT_GE(d.markers_in_range, 40);
  EXPECT_GE(d.recall(), 0.95);
  EXPECT_GE(d.precision(), 0.99);
  EXPECT_LT(d.marker_centre.mean_m, 0.015);
  ASSERT_GE(d.lights_visible, 10);
  EXPECT_GE(d.lights_found, d.lights_visible * 9 / 10);
  EXPECT_LT(d.light_centre.mean_m, 0.05);
}

}  // namespace
}  // namespace irgs::vision
