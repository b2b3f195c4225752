#include "core/navigation/heading_controller.hpp"

#include <algorithm>
#include <cmath>

namespace irgs {

double moveVectorAngle(const Vec2& move_body) {
  if (move_body.x() == 0.0 && move_body.y() == 0.0)
    return 0.0;
  return std::atan2(move_body.y(), move_body.x());
}

VelocityCommand trackMoveVector(const HeadingControlParams& params, const Vec2& move_body,
                                double speed_mps) {
  const double alpha = moveVectorAngle(move_body);
  const double w =
      std::clamp(params.k_theta * alpha, -params.max_turn_rate_radps, params.max_turn_rate_radps);
  double v = 0.0;
  if (std::abs(alpha) < params.turn_in_place_rad) {
    const double c = std::max(0.0, std::cos(alpha));
    v = speed_mps * c * c;
  }
  return {v, w};
}

WheelCommand wheelSpeedsFor(double v_mps, double w_radps, double wheel_separation_m) {
  return {v_mps - 0.5 * w_radps * wheel_separation_m, v_mps + 0.5 * w_radps * wheel_separation_m};
}

VelocityCommand bodyVelocityFrom(const WheelCommand& wheels, double wheel_separation_m) {
  return {0.5 * (wheels.right_mps + wheels.left_mps),
          (wheels.right_mps - wheels.left_mps) / wheel_separation_m};
}

}  // namespace irgs
