#pragma once
// Local obstacle avoidance of 002_… 3.3 (Figs. 3, 16): a VFH-like vector sum over the sonars.
//
// A002-8 resolves the wording: each sensor i contributes along its unit direction u_i (body
// frame) with a proximity weight w(d_i) = max(0, (d_infl - d_i) / d_infl), and the repulsive
// vector is the NEGATED weighted sum
//     V_Repulsive_Sum = -k_rep * sum_i w(d_i) u_i,      V_Move = V_Target + V_Repulsive_Sum.
// Body frame: x forward, y left (the paper's robot y forward is our x).

#include <span>

#include "core/geometry/types.hpp"

namespace irgs {

struct AvoidanceParams {
  double k_rep = 1.2;        // gain of the repulsive sum (no paper value)
  double influence_m = 1.0;  // d_infl: readings beyond it push nothing (no paper value)
  double target_gain = 1.0;  // length of V_Target (a unit direction times this)
};

// One sonar's latest reading in the body frame.
struct SonarRay {
  Vec2 direction = Vec2::UnitX();  // unit, body frame
  double range_m = 0.0;            // distance to the echo (max range when nothing was seen)
};

// w(d) of A002-8.
double repulsionWeight(const AvoidanceParams& params, double range_m);

// V_Repulsive_Sum of A002-8.
Vec2 repulsiveSum(const AvoidanceParams& params, std::span<const SonarRay> rays);

// V_Move = target_gain * unit(target) + repulsive (a zero target contributes nothing).
Vec2 moveVector(const AvoidanceParams& params, const Vec2& target_body, const Vec2& repulsive);

}  // namespace irgs
