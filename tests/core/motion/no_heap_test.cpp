// Firmware-grade: after construction the motion executor never allocates. Every allocation of
// this test program is counted (global operator new), and the executor's start, step and
// report calls — every primitive kind, run to its end on the simulator — must add none.

#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "core/motion/host_adapters.hpp"
#include "core/motion/motion_executor.hpp"
#include "core/sim/sim_presets.hpp"
#include "tests/core/behaviour/behaviour_test_support.hpp"

namespace {
bool g_counting = false;
long g_allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
  if (g_counting)
    ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size))
    return p;
  throw std::bad_alloc();
}
// GCC cannot see that these pair with the operator new above (its malloc).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace irgs::motion {
namespace {

// Counts the allocations inside f().
template <class F>
auto counted(F f) {
  g_counting = true;
  auto result = f();
  g_counting = false;
  return result;
}

TEST(MotionExecutor, StartStepAndReportsNeverAllocate) {
  const WorldMap map = test::loadBundledMap("thesis_sim1_loop");
  const RobotProfile profile = test::thesisRobot();
  Simulator sim(map, profile, idealSimConfig());
  sim.resetPose(map.start);
  MotionExecutor executor(motionGeometryOf(profile));

  TurnSpec turn;
  turn.angle_rad = 2.0;
  DriveSpec drive;
  drive.distance_m = 0.5;
  FollowWallSpec follow;
  follow.travel_limit_m = 3.0;
  follow.report_every_m = 0.5;
  SegmentsSpec segments;
  segments.append(map.start.position() + Vec2(0.3, 0.0));
  segments.append(map.start.position() + Vec2(0.3, 0.3));
  FollowPathSpec path;
  path.append(map.start.position() + Vec2(0.4, 0.0));
  const PrimitiveSpec specs[] = {turn, drive, follow, segments, path};

  TelemetrySample sample = sim.step();
  std::uint16_t id = 0;
  long steps = 0;
  for (const PrimitiveSpec& spec : specs) {
    const MotionInput start = motionInputOf(sample);
    ASSERT_TRUE(counted([&] { return executor.start({++id, spec}, start); }));
    for (int i = 0; i < 6000 && executor.running(); ++i, ++steps) {
      const MotionInput in = motionInputOf(sample);
      sim.setCommand(counted([&] { return executor.step(in); }));
      MotionReport r;
      while (counted([&] { return executor.popReport(r); })) {
      }
      sim.step(sample);
    }
  }
  EXPECT_GT(steps, 1000);
  EXPECT_EQ(g_allocations, 0);
}

}  // namespace
}  // namespace irgs::motion
