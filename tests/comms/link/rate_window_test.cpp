#include "comms/link/rate_window.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace irgs::comms {
namespace {

TEST(RateWindow, SumsWhatWasAddedWithinTheWindow) {
  RateWindow w(2.0);
  for (int i = 0; i < 20; ++i)
    w.add(0.1 * i, 10.0);  // 100 units/s during [0, 2)
  EXPECT_DOUBLE_EQ(w.sum(1.95), 200.0);
  EXPECT_DOUBLE_EQ(w.ratePerSecond(1.95), 100.0);
}

TEST(RateWindow, ForgetsValuesOlderThanTheWindow) {
  RateWindow w(1.0);
  w.add(0.0, 5.0);
  w.add(0.55, 7.0);
  EXPECT_DOUBLE_EQ(w.sum(0.9), 12.0);
  EXPECT_DOUBLE_EQ(w.sum(1.2), 7.0);
  EXPECT_DOUBLE_EQ(w.sum(10.0), 0.0);
  w.add(10.0, 1.0);  // a bucket slot reused after wrapping starts from zero
  EXPECT_DOUBLE_EQ(w.sum(10.0), 1.0);
}

TEST(RateWindow, RejectsANonPositiveWindow) {
  EXPECT_THROW(RateWindow(0.0), std::invalid_argument);
  EXPECT_THROW(RateWindow(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
