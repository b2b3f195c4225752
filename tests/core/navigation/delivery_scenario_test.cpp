#include "core/scenario/delivery_scenario.hpp"

#include <gtest/gtest.h>

#include "core/robot/robot_profile_file.hpp"
#include "core/world/map_file.hpp"

namespace irgs {
namespace {

DeliveryScenarioSpec spec(const char* map_file, std::uint64_t seed) {
  const std::string root = IRGS_SOURCE_DIR;
  DeliveryScenarioSpec s;
  s.map = *loadMapFile(root + "/resources/maps/" + map_file).map;
  s.profile = *loadRobotProfileFile(root + "/resources/robots/delivery_002.json").profile;
  s.from_node = "0";
  s.to_node = "6";
  s.sim = typicalSimConfig();
  s.sim.seed = seed;
  return s;
}

TEST(DeliveryScenario, NodeZeroToSixOnTheBundledFloorArrivesWithoutContact) {
  const DeliveryScenarioResult r = runDeliveryScenario(spec("delivery_floor_002.json", 1));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.delivery.arrived);
  EXPECT_TRUE(r.delivery.success);
  EXPECT_EQ(r.delivery.collisions, 0);
  EXPECT_LT(r.delivery.goal_error_m, 0.5);
  EXPECT_EQ(r.delivery.markers_acted, 4);  // nodes 1, 5, 4 and the stop at 6
  EXPECT_GT(r.delivery.min_clearance_m, 0.05);
  // One trajectory row every 0.5 s (Fig. 23).
  const auto& rows = r.run.scenario.trajectory;
  ASSERT_GE(rows.size(), 3u);
  EXPECT_NEAR(rows[2].time_s - rows[1].time_s, 0.5, 1e-9);
}

TEST(DeliveryScenario, MovingObstaclesAreAvoided) {
  const DeliveryScenarioResult r = runDeliveryScenario(spec("delivery_floor_002_people.json", 2));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.delivery.success);
  EXPECT_EQ(r.delivery.collisions, 0);
}

TEST(DeliveryScenario, UnknownNodesAreReported) {
  DeliveryScenarioSpec s = spec("delivery_floor_002.json", 1);
  s.to_node = "N42";
  EXPECT_NE(runDeliveryScenario(s).error.find("unknown node"), std::string::npos);
}

}  // namespace
}  // namespace irgs
