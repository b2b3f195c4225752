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

TEST(SimOptions, BehaviourTakesMapbuildGoalOrCoverage) {
  const auto r = parseSimOptions({"--map", "m", "--out", "o", "--behaviour", "mapbuild"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->behaviour, "mapbuild");
  const auto g =
      parseSimOptions({"--map", "m", "--out", "o", "--behaviour", "goal", "--goal", "4.5,-2"});
  ASSERT_TRUE(g.options) << g.error;
  ASSERT_TRUE(g.options->goal);
  EXPECT_DOUBLE_EQ(g.options->goal->x(), 4.5);
  EXPECT_DOUBLE_EQ(g.options->goal->y(), -2.0);
  EXPECT_TRUE(parseSimOptions({"--map", "m", "--out", "o", "--behaviour", "coverage"}).options);
}

TEST(SimOptions, BehaviourRefusesWhatItCannotRun) {
  const auto error = [](std::vector<std::string> args) { return parseSimOptions(args).error; };
  EXPECT_NE(error({"--map", "m", "--out", "o", "--behaviour", "dance"}).find("mapbuild"),
            std::string::npos);
  EXPECT_NE(error({"--map", "m", "--out", "o", "--behaviour", "goal"}).find("--goal"),
            std::string::npos);
  EXPECT_NE(error({"--map", "m", "--out", "o", "--behaviour", "goal", "--goal", "1"}).find("X,Y"),
            std::string::npos);
  EXPECT_NE(error({"--map", "m", "--out", "o", "--goal", "1,2"}).find("--behaviour goal"),
            std::string::npos);
  EXPECT_NE(error({"--map", "m", "--out", "o", "--behaviour", "mapbuild", "--script", "s"})
                .find("--script"),
            std::string::npos);
  EXPECT_NE(error({"--map", "m", "--out", "o", "--compare", "a/grid.yaml"}).find("mapbuild"),
            std::string::npos);
  EXPECT_NE(error({"--map", "m", "--out", "o", "--behaviour", "mapbuild", "--compare", ""})
                .find("--compare"),
            std::string::npos);
}

}  // namespace
}  // namespace irgs::app

namespace irgs::app {
namespace {

TEST(SimOptions, ConnectTakesAUrlAndMakesTheMapOptional) {
  const auto r = parseSimOptions(
      {"--connect", "serial:///dev/pts/7?baud=115200", "--out", "o", "--connect-timeout", "2.5"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->connect, "serial:///dev/pts/7?baud=115200");
  EXPECT_DOUBLE_EQ(r.options->connect_timeout_s, 2.5);
  EXPECT_TRUE(r.options->map.empty());
  EXPECT_DOUBLE_EQ(parseSimOptions({"--map", "m", "--out", "o"}).options->connect_timeout_s, 10.0);
}

TEST(SimOptions, ConnectRunsABehaviourFromADeclaredStartAndComparesWithASavedMap) {
  const auto r = parseSimOptions({"--connect", "tcp://localhost:8101?protocol=arcos", "--out", "o",
                                  "--map", "m.json", "--start", "1,2,90", "--behaviour", "mapbuild",
                                  "--compare", "inprocess/grid.yaml"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->behaviour, "mapbuild");
  ASSERT_TRUE(r.options->start);
  EXPECT_DOUBLE_EQ(r.options->start->y, 2.0);
  EXPECT_EQ(r.options->compare, "inprocess/grid.yaml");
  const auto goal = parseSimOptions({"--connect", "tcp://h:1", "--out", "o", "--map", "m.json",
                                     "--behaviour", "goal", "--goal", "1,1"});
  ASSERT_TRUE(goal.options) << goal.error;
}

TEST(SimOptions, ConnectRefusesWhatOnlyTheSimulatorCanDo) {
  EXPECT_NE(parseSimOptions({"--connect", "/dev/ttyUSB0", "--out", "o"}).error.find("URL"),
            std::string::npos);
  EXPECT_NE(
      parseSimOptions({"--connect", "tcp://h:1", "--out", "o", "--ideal"}).error.find("--ideal"),
      std::string::npos);
  EXPECT_NE(parseSimOptions({"--connect", "tcp://h:1", "--out", "o", "--connect-timeout", "0"})
                .error.find("--connect-timeout"),
            std::string::npos);
  EXPECT_NE(parseSimOptions({"--connect", "tcp://h:1"}).error.find("--out"), std::string::npos);
}

TEST(SimOptions, ASigningKeyFileGoesWithConnect) {
  const auto r =
      parseSimOptions({"--connect", "tcp://h:1", "--out", "o", "--signing-key", "robot.key"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->signing_key, "robot.key");
  EXPECT_NE(parseSimOptions({"--map", "m", "--out", "o", "--signing-key", "robot.key"})
                .error.find("needs --connect"),
            std::string::npos);
}

}  // namespace
}  // namespace irgs::app
