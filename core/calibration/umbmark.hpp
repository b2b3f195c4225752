#pragma once
// UMBmark (Borenstein & Feng 1996, "Measurement and correction of systematic odometry errors in
// mobile robots"): the math from measured return errors to the two systematic corrections of a
// differential drive, and the paper's error measure. The derivation in our frames (x forward,
// y left, theta CCW) is in docs/calibration.md; equation tags (U1)...(U8) refer to it.
//
// A run: the robot starts at the origin facing +x and drives, on its own odometry, a square of
// side L clockwise (right turns) or counter-clockwise (left turns), stopping where it believes
// it started. Its return error is eps = true final position - odometry final position, in the
// start frame (the paper's eps_x = x_abs - x_calc), metres.
//
// The two error sources (relative to the odometry's current belief):
//   E_d = D_R / D_L  wheel diameter ratio (> 1: right wheel larger, the robot curves left),
//   E_b = b_actual / b_believed  wheelbase ratio (> 1: every turn falls short).
// Corrections (paper eq. 17): c_L = 2 / (E_d + 1), c_R = 2 / (1 / E_d + 1) multiply the
// odometry's left/right wheel travel; the believed wheelbase is multiplied by E_b.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

enum class UmbmarkDirection { kClockwise, kCounterClockwise };

const char* toString(UmbmarkDirection direction);

// One measured run: the return error (true - believed final position), start frame, metres.
struct UmbmarkRun {
  UmbmarkDirection direction = UmbmarkDirection::kClockwise;
  Vec2 error_m = Vec2::Zero();
};

struct UmbmarkSetup {
  double side_m = 4.0;       // L, the square's side (the paper's 4 m)
  double wheelbase_m = 0.0;  // b, the wheelbase the odometry used during the runs (> 0)
};

struct UmbmarkAnalysis {
  bool ok = false;  // false: see diagnostics (too few runs, non-finite data, no solution)
  std::vector<std::string> diagnostics;
  std::size_t cw_runs = 0;
  std::size_t ccw_runs = 0;
  // (U1) centres of gravity of the return errors, start frame, metres.
  Vec2 cg_cw = Vec2::Zero();
  Vec2 cg_ccw = Vec2::Zero();
  // (U2) the paper's measure of systematic odometry error: max(|cg_cw|, |cg_ccw|), metres.
  double e_max_syst_m = 0.0;
  // Spread of the runs about their centre of gravity (rms distance), metres: the random part.
  double spread_cw_m = 0.0;
  double spread_ccw_m = 0.0;

  // The paper's closed-form small-error estimates (U3)-(U6): alpha = turn shortfall per 90 deg
  // turn, beta = heading change per leg (CCW positive), both radians.
  double alpha_rad = 0.0;
  double beta_rad = 0.0;
  double radius_m = 0.0;  // (U5) radius of the curved leg; infinite when beta = 0
  double wheel_diameter_ratio_linear = 1.0;  // (U6) E_d
  double wheelbase_ratio_linear = 1.0;       // (U7) E_b
  // The same two numbers from the exact forward model (U8) fitted to all four centre-of-gravity
  // coordinates by Gauss-Newton, started at the closed form: what the corrections use.
  double wheel_diameter_ratio = 1.0;  // E_d
  double wheelbase_ratio = 1.0;       // E_b
  double fit_residual_m = 0.0;        // rms of the model's misfit to the four coordinates
};

// Analyses n >= 1 runs per direction. Non-finite errors are skipped with a diagnostic; fewer than
// one usable run per direction, or errors too large for the model (more than L / 2), make the
// result not ok. Throws std::invalid_argument for a non-positive or non-finite setup.
UmbmarkAnalysis analyseUmbmark(std::span<const UmbmarkRun> runs, const UmbmarkSetup& setup);

// (U8) The exact forward model: the return error of one run for a robot whose odometry believes
// a wheelbase b = setup.wheelbase_m, with true wheel diameter ratio E_d (mean diameter right) and
// wheelbase ratio E_b, driving the square with on-the-spot turns and straight legs as its
// odometry sees them (a constant-curvature arc in truth). Throws std::invalid_argument for
// non-positive or non-finite arguments.
Vec2 predictUmbmarkError(UmbmarkDirection direction, const UmbmarkSetup& setup,
                         double wheel_diameter_ratio, double wheelbase_ratio);

// Odometry corrections (paper eq. 17) for a drive whose odometry currently uses per-wheel travel
// factors left/right and wheelbase b, after a UMBmark that found E_d, E_b: the new factors are
// the old ones times c_L, c_R, normalised to mean 1 (UMBmark cannot see the mean wheel size),
// the new wheelbase is b * E_b.
struct OdometryCorrection {
  double left_wheel_scale = 1.0;
  double right_wheel_scale = 1.0;
  double wheelbase_m = 0.0;
};
OdometryCorrection correctOdometry(const OdometryCorrection& current, double wheel_diameter_ratio,
                                   double wheelbase_ratio);

}  // namespace irgs
