#include "app/sim/sim_options.hpp"

#include <gtest/gtest.h>

namespace irgs::app {
namespace {

TEST(SimOptions, ParsesEveryOption) {
  const auto r = parseSimOptions({"--map", "m.json", "--out", "o", "--robot", "r.json", "--start",
                                  "1.5,-2,90", "--script", "s.txt", "--seed", "42", "--duration",
                                  "12.5", "--resolution", "0.02", "--ideal", "--quiet"});
  ASSERT_TRUE(r.options) << r.error;
  const SimOptions& o = *r.options;
  EXPECT_EQ(o.map, "m.json");
  EXPECT_EQ(o.out, "o");
  EXPECT_EQ(o.robot, "r.json");
  ASSERT_TRUE(o.start);
  EXPECT_DOUBLE_EQ(o.start->x, 1.5);
  EXPECT_DOUBLE_EQ(o.start->y, -2.0);
  EXPECT_NEAR(o.start->theta, kPi / 2.0, 1e-12);
  EXPECT_EQ(o.script, "s.txt");
  EXPECT_EQ(o.seed, 42u);
  EXPECT_DOUBLE_EQ(*o.duration_s, 12.5);
  EXPECT_DOUBLE_EQ(o.grid_resolution_m, 0.02);
  EXPECT_TRUE(o.ideal);
  EXPECT_TRUE(o.quiet);
}

TEST(SimOptions, DefaultsWhenOnlyMapAndOutAreGiven) {
  const auto r = parseSimOptions({"--map", "m.json", "--out", "o"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->seed, 1u);
  EXPECT_FALSE(r.options->start);
  EXPECT_FALSE(r.options->duration_s);
  EXPECT_TRUE(r.options->robot.empty());
  EXPECT_DOUBLE_EQ(r.options->grid_resolution_m, 0.01);
}

TEST(SimOptions, HelpIsNotAnError) {
  const auto r = parseSimOptions({"--help"});
  EXPECT_TRUE(r.help);
  EXPECT_FALSE(r.options);
}

TEST(SimOptions, BadArgumentsSayWhatIsWrong) {
  EXPECT_NE(parseSimOptions({"--out", "o"}).error.find("--map"), std::string::npos);
  EXPECT_NE(parseSimOptions({"--map", "m"}).error.find("--out"), std::string::npos);
  EXPECT_NE(parseSimOptions({"--map", "m", "--out", "o", "--seed", "-3"}).error.find("--seed"),
            std::string::npos);
  EXPECT_NE(parseSimOptions({"--map", "m", "--out", "o", "--start", "1,2"}).error.find("--start"),
            std::string::npos);
  EXPECT_NE(
      parseSimOptions({"--map", "m", "--out", "o", "--duration", "0"}).error.find("--duration"),
      std::string::npos);
  EXPECT_NE(
      parseSimOptions({"--map", "m", "--out", "o", "--duration", "nan"}).error.find("--duration"),
      std::string::npos);
  EXPECT_NE(parseSimOptions({"--map", "m", "--out", "o", "--fast", "1"}).error.find("--fast"),
            std::string::npos);
  EXPECT_NE(parseSimOptions({"--map"}).error.find("needs a value"), std::string::npos);
  EXPECT_NE(parseSimOptions({"stray"}).error.find("stray"), std::string::npos);
}

}  // namespace
}  // namespace irgs::app
