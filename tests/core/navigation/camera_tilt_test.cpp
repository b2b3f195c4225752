#include "core/navigation/camera_tilt.hpp"

#include <gtest/gtest.h>

#include "core/geometry/types.hpp"

namespace irgs {
namespace {

TEST(CameraTilt, ThirtyFiveDegreesFarNinetyOverheadLinearBetween) {
  const CameraTiltLaw law;  // 35 deg beyond 3 m, 90 deg within 0.3 m
  EXPECT_NEAR(radToDeg(tiltForDistance(law, 10.0)), 35.0, 1e-9);
  EXPECT_NEAR(radToDeg(tiltForDistance(law, 3.0)), 35.0, 1e-9);
  EXPECT_NEAR(radToDeg(tiltForDistance(law, 0.0)), 90.0, 1e-9);
  EXPECT_NEAR(radToDeg(tiltForDistance(law, 1.65)), 62.5, 1e-9);  // halfway
}

TEST(CameraTilt, TiltFromVerticalIsZeroOverheadAndRiseGoesFromZeroToOne) {
  const CameraTiltLaw law;
  EXPECT_NEAR(tiltFromVertical(degToRad(90.0)), 0.0, 1e-12);
  EXPECT_NEAR(radToDeg(tiltFromVertical(degToRad(35.0))), 55.0, 1e-9);
  EXPECT_NEAR(tiltRise(law, law.far_tilt_rad), 0.0, 1e-12);
  EXPECT_NEAR(tiltRise(law, law.near_tilt_rad), 1.0, 1e-12);
  EXPECT_NEAR(tiltRise(law, degToRad(62.5)), 0.5, 1e-9);
}

}  // namespace
}  // namespace irgs
