#pragma once
// A behaviour driving the simulator the way it drives a Pioneer over ARCOS: it sees telemetry
// only every period_s (a SIP every 100 ms, carrying the latest reading of each sonar disc of
// that cycle), its answer reaches the wheels delay_s later, RVEL rounds the turn rate to whole
// deg/s and ROTVEL reports the measured one in 0.1 deg/s; a drive commanded but not moving for
// 0.2 s reports a stall (the Pioneers have no bumper switches). In-process, by contrast, the
// behaviour sees every 10 ms step and its answer applies at the next one.
//
// A loaded ground station (jitter_s > 0 or freeze_probability > 0): each answer is a further
// uniform [0, jitter_s] late, and with freeze_probability per answer the station stalls for
// 0.2-1 s, during which nothing it answers reaches the wheels; answers keep their order. Seeded.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <vector>

#include "core/behaviour/behaviour.hpp"
#include "core/sim/simulator.hpp"

namespace irgs::test {

struct SampledLink {
  double period_s = 0.1;
  double delay_s = 0.1;
  double jitter_s = 0.0;
  double freeze_probability = 0.0;
  unsigned seed = 1;
};

struct SampledLinkRun {
  bool finished = false;
  bool failed = false;
  double time_s = 0.0;  // simulated, when the behaviour finished (or the budget)
  // Answers with v = 0 whose turn rate has the opposite sign to the previous non-zero turn rate
  // of the same on-the-spot turn: the robot hunting across its target heading.
  int turn_reversals = 0;
  int spot_turns = 0;                // runs of answers with v = 0 and some w != 0
  double longest_spot_turn_s = 0.0;  // the longest of them
  double longest_stall_s = 0.0;      // the longest stretch with drive_stalled reported
};

inline double roundToWholeDegPerSecond(double w_radps) {
  return degToRad(std::round(radToDeg(w_radps)));
}

inline SampledLinkRun runOverSampledLink(Simulator& sim, Behaviour& behaviour,
                                         const SampledLink& link, double budget_s) {
  const double dt = sim.config().dt_s;
  const auto steps_per_sample = std::max<long>(1, std::lround(link.period_s / dt));
  const auto delay_steps = std::lround(link.delay_s / dt);
  struct Pending {
    long apply_step;
    VelocityCommand command;
  };
  std::deque<Pending> pending;
  std::mt19937 rng(link.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  long frozen_until_step = 0;
  long last_apply_step = 0;
  std::vector<std::optional<SonarReading>> latest(sim.profile().sonars.size());
  SampledLinkRun run;
  TelemetrySample step_sample;
  double stalled_s = 0.0;
  double previous_turn_sign = 0.0;
  bool in_spot_turn = false;  // the answers since spot_turn_start_s all had v = 0
  double spot_turn_start_s = 0.0;
  bool spot_turn_rotates = false;
  const auto total_steps = std::lround(budget_s / dt);
  for (long step = 1; step <= total_steps; ++step) {
    while (!pending.empty() && pending.front().apply_step <= step) {
      sim.setCommand(pending.front().command);
      pending.pop_front();
    }
    sim.step(step_sample);
    for (const SonarReading& r : step_sample.sonar)
      latest[static_cast<std::size_t>(r.sensor)] = r;
    const VelocityCommand& commanded = sim.command();
    const VelocityCommand moving = sim.trueVelocity();
    const bool drives =
        std::abs(commanded.linear_mps) > 1e-3 || std::abs(commanded.angular_radps) > 1e-3;
    const bool moves = std::abs(moving.linear_mps) > 1e-4 || std::abs(moving.angular_radps) > 1e-4;
    stalled_s = drives && !moves ? stalled_s + dt : 0.0;
    if (step % steps_per_sample != 0)
      continue;

    TelemetrySample sample = step_sample;
    sample.sonar.clear();
    for (auto& r : latest) {
      if (r)
        sample.sonar.push_back(*r);
      r.reset();
    }
    sample.measured_velocity.angular_radps =
        degToRad(std::round(radToDeg(sample.measured_velocity.angular_radps) * 10.0) / 10.0);
    sample.drive_stalled = stalled_s > 0.2;
    run.longest_stall_s = std::max(run.longest_stall_s, stalled_s);
    VelocityCommand answer = behaviour.onSample(sample);
    answer.angular_radps = roundToWholeDegPerSecond(answer.angular_radps);
    long apply_step = step + std::max<long>(1, delay_steps);
    if (link.jitter_s > 0.0)
      apply_step += std::lround(uniform(rng) * link.jitter_s / dt);
    if (step >= frozen_until_step && link.freeze_probability > 0.0 &&
        uniform(rng) < link.freeze_probability)
      frozen_until_step = step + std::lround((0.2 + 0.8 * uniform(rng)) / dt);
    apply_step = std::max({apply_step, frozen_until_step, last_apply_step});
    last_apply_step = apply_step;
    pending.push_back({apply_step, answer});

    const double t = sample.time_s;
    if (answer.linear_mps == 0.0) {
      if (!in_spot_turn) {
        in_spot_turn = true;
        spot_turn_start_s = t;
      }
      if (answer.angular_radps != 0.0) {
        if (!spot_turn_rotates)
          ++run.spot_turns;
        spot_turn_rotates = true;
        const double sign = std::copysign(1.0, answer.angular_radps);
        if (previous_turn_sign != 0.0 && sign != previous_turn_sign)
          ++run.turn_reversals;
        previous_turn_sign = sign;
      }
      if (spot_turn_rotates)
        run.longest_spot_turn_s = std::max(run.longest_spot_turn_s, t - spot_turn_start_s);
    } else {
      in_spot_turn = false;
      spot_turn_rotates = false;
      previous_turn_sign = 0.0;
    }

    const BehaviourStatus status = behaviour.status();
    run.time_s = t;
    if (status.finished) {
      run.finished = true;
      run.failed = status.failed;
      break;
    }
  }
  return run;
}

}  // namespace irgs::test
