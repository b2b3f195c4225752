#include "core/navigation/camera_tilt.hpp"

#include <gtest/gtest.h>

#include "core/geometry/types.hpp"
#include "core/navigation/landmark_navigator.hpp"

namespace irgs {
namespace {

TEST(CameraTilt, NavigationDefaultIsThirtyFiveDegreesFromThreeMetresToNinetyOverhead) {
  const TiltLaw law = LandmarkNavigatorParams{}.tilt;
  EXPECT_NEAR(radToDeg(law.tiltFor(10.0)), 35.0, 1e-9);
  EXPECT_NEAR(radToDeg(law.tiltFor(3.0)), 35.0, 1e-9);
  EXPECT_NEAR(radToDeg(law.tiltFor(0.0)), 90.0, 1e-9);
  EXPECT_NEAR(radToDeg(law.tiltFor(1.65)), 62.5, 1e-9);  // halfway
}

TEST(CameraTilt, RiseGoesFromZeroFarToOneOverhead) {
  const TiltLaw law = LandmarkNavigatorParams{}.tilt;
  EXPECT_NEAR(tiltFromVertical(degToRad(90.0)), 0.0, 1e-12);
  EXPECT_NEAR(tiltRise(law, law.min_tilt_rad), 0.0, 1e-12);
  EXPECT_NEAR(tiltRise(law, law.max_tilt_rad), 1.0, 1e-12);
  EXPECT_NEAR(tiltRise(law, degToRad(62.5)), 0.5, 1e-9);
  EXPECT_NEAR(tiltRise(law, degToRad(20.0)), 0.0, 1e-12);
}

}  // namespace
}  // namespace irgs
