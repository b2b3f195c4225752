#pragma once
// The robot side of a primitive in-process: a Simulator stepped with a MotionExecutor, as the
// in-process simulated robot and irgs-robot do, collecting every report.

#include <vector>

#include "core/motion/host_adapters.hpp"
#include "core/motion/motion_executor.hpp"
#include "core/sim/simulator.hpp"

namespace irgs::test {

struct PrimitiveRun {
  std::vector<motion::MotionReport> reports;
  bool finished = false;
  double time_s = 0.0;
  Pose2 odometry;
  Pose2 truth;

  // The kinds in order.
  std::vector<motion::ReportKind> kinds() const {
    std::vector<motion::ReportKind> k;
    for (const auto& r : reports)
      k.push_back(r.kind);
    return k;
  }
  const motion::MotionReport& last() const { return reports.back(); }
};

// Starts `primitive` on the robot at the simulator's current state and steps until it ends or
// budget_s has passed.
inline PrimitiveRun runPrimitive(Simulator& sim, motion::MotionExecutor& executor,
                                 const motion::Primitive& primitive, double budget_s) {
  PrimitiveRun run;
  TelemetrySample sample = sim.step();
  executor.start(primitive, motion::motionInputOf(sample));
  const double end = sim.time_s() + budget_s;
  motion::MotionReport r;
  while (sim.time_s() < end) {
    while (executor.popReport(r))
      run.reports.push_back(r);
    if (!run.reports.empty() && motion::isFinal(run.reports.back().kind)) {
      run.finished = true;
      break;
    }
    sim.setCommand(executor.step(motion::motionInputOf(sample)));
    sim.step(sample);
  }
  run.time_s = sim.time_s();
  run.odometry = sim.odometryPose();
  run.truth = sim.truePose();
  return run;
}

}  // namespace irgs::test
