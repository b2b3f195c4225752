// The plots' data layer: the ring buffer and the min/max decimation.

#include "widgets/plots/plot_series.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace irgs::widgets {
namespace {

TEST(PlotSeries, KeepsTheNewestSamplesWhenFull) {
  PlotSeries s(4);
  for (int i = 0; i < 10; ++i)
    EXPECT_TRUE(s.append(i * 0.1, i));
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s.oldest().value, 6.0);
  EXPECT_DOUBLE_EQ(s.newest().value, 9.0);
  EXPECT_DOUBLE_EQ(s.at(1).value, 7.0);
}

TEST(PlotSeries, GrowsWithItsSamplesUpToTheCapacityAndWrapsAfterAClear) {
  PlotSeries s(1000);
  EXPECT_EQ(s.capacity(), 1000u);
  for (int i = 0; i < 2500; ++i)
    ASSERT_TRUE(s.append(i * 0.01, i));
  ASSERT_EQ(s.size(), 1000u);
  EXPECT_DOUBLE_EQ(s.oldest().value, 1500.0);
  EXPECT_DOUBLE_EQ(s.newest().value, 2499.0);
  std::size_t n = 0;
  double expected = 1500.0;
  s.forEach(0, s.size(), [&](const PlotSample& p) {
    EXPECT_DOUBLE_EQ(p.value, expected++);
    ++n;
  });
  EXPECT_EQ(n, 1000u);
  s.clear();
  for (int i = 0; i < 1003; ++i)
    ASSERT_TRUE(s.append(100.0 + i * 0.01, -i));
  ASSERT_EQ(s.size(), 1000u);
  EXPECT_DOUBLE_EQ(s.oldest().value, -3.0);
  EXPECT_DOUBLE_EQ(s.at(500).value, -503.0);
  EXPECT_DOUBLE_EQ(s.newest().value, -1002.0);
}

TEST(PlotSeries, DropsNonFiniteAndOutOfOrderSamplesAndRestartsOnALargeStepBack) {
  PlotSeries s(16);
  EXPECT_TRUE(s.append(5.0, 1.0));
  EXPECT_FALSE(s.append(5.1, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(s.append(std::numeric_limits<double>::infinity(), 1.0));
  EXPECT_FALSE(s.append(4.5, 2.0));  // back by less than kRestartGap_s: out of order
  EXPECT_EQ(s.size(), 1u);
  EXPECT_TRUE(s.append(0.0, 3.0));  // back by 5 s: a new run
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s.newest().value, 3.0);
}

TEST(PlotSeries, RangeAndSamplesCoverTheClosedWindow) {
  PlotSeries s(100);
  for (int i = 0; i <= 10; ++i)
    s.append(i, (i % 3) - 1.0);
  EXPECT_EQ(s.lowerBound(2.5), 3u);
  EXPECT_EQ(s.lowerBound(100.0), s.size());
  const auto r = s.range(2.0, 4.0);  // values at 2,3,4: 1, -1, 0
  ASSERT_TRUE(r.has_value());
  EXPECT_DOUBLE_EQ(r->min, -1.0);
  EXPECT_DOUBLE_EQ(r->max, 1.0);
  EXPECT_FALSE(s.range(20.0, 30.0).has_value());
  EXPECT_EQ(s.samples(2.0, 4.0).size(), 3u);
}

TEST(PlotSeries, DecimationKeepsEveryExtremeInBoundedColumns) {
  PlotSeries s(100000);
  // 10 minutes at 50 Hz of a sine with one spike that a naive every-nth thinning would miss.
  for (int i = 0; i < 30000; ++i) {
    const double t = i * 0.02;
    s.append(t, i == 12345 ? 50.0 : std::sin(t));
  }
  const auto columns = s.decimate(0.0, 600.0, 500);
  ASSERT_LE(columns.size(), 500u);
  ASSERT_GE(columns.size(), 490u);
  double max = -1e9;
  double min = 1e9;
  for (const PlotColumn& c : columns) {
    max = std::max(max, c.max);
    min = std::min(min, c.min);
    EXPECT_LE(c.min, c.first);
    EXPECT_LE(c.min, c.last);
    EXPECT_GE(c.max, c.first);
    EXPECT_GE(c.max, c.last);
  }
  EXPECT_DOUBLE_EQ(max, 50.0);
  EXPECT_NEAR(min, -1.0, 1e-3);
}

TEST(PlotSeries, SparseWindowsComeBackOneColumnPerSample) {
  PlotSeries s(100);
  for (int i = 0; i < 10; ++i)
    s.append(i, i * 2.0);
  const auto columns = s.decimate(2.0, 5.0, 100);
  ASSERT_EQ(columns.size(), 4u);
  EXPECT_DOUBLE_EQ(columns[0].time_s, 2.0);
  EXPECT_DOUBLE_EQ(columns[3].last, 10.0);
  EXPECT_TRUE(s.decimate(5.0, 2.0, 100).empty());
  EXPECT_TRUE(s.decimate(2.0, 5.0, 0).empty());
}

}  // namespace
}  // namespace irgs::widgets
