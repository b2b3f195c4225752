#pragma once
// Observability of the 001_… dead-reckoning error models by the total observability matrix
// (TOM) of a piecewise-constant system (digest 2.5, (11)-(14)):
//   Q_j = [H; H F_j; ...; H F_j^(n-1)]                                      (13)
//   TOM = [Q_1; Q_2 F_1^(n-1); ...; Q_r F_(r-1)^(n-1) ... F_1^(n-1)]         (14)
// for the 9-state model (9)/(10), the 8-state model (15)/(16) with dtheta = dpsi - dphi and the
// 7-state heading-only model (17)/(18), all reconstructed per A001-3/A001-5 and in the project
// frame (A001-2). Sizes differ per model, so the matrices here are dynamic (an analysis tool,
// not a filter).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace irgs {

enum class DrModelKind { kNineState, kEightState, kSevenState };

int stateCount(DrModelKind kind);
// State names in model order ("dx", "dy", "dpsi", "S_R", ...).
std::vector<std::string> stateNames(DrModelKind kind);

// One constant segment: per-step encoder increments R, L [m], heading psi [rad], gyro angle
// increment Omega [rad], wheelbase D [m], step dt [s].
struct DrSegment {
  double right_m = 0.0;
  double left_m = 0.0;
  double psi_rad = 0.0;
  double omega_rad = 0.0;
  double wheelbase_m = 0.5;
  double dt_s = 1.0;
};

// How the gyro increment of random segments relates to the encoders.
enum class SegmentKind {
  kConsistent,   // Omega = (R - L) / D: the gyro sees the rotation the wheels make (physical)
  kIndependent,  // Omega drawn independently of R, L (the digest's numerical check)
};

// `count` random segments, deterministic for the seed (SimRandom): R, L in [-0.5, 0.5] m,
// psi in [-pi, pi), Omega per `kind`.
std::vector<DrSegment> randomSegments(int count, std::uint64_t seed, SegmentKind kind,
                                      double wheelbase_m = 0.5, double dt_s = 1.0);

Eigen::MatrixXd drTransitionMatrix(DrModelKind kind, const DrSegment& segment);
Eigen::RowVectorXd drMeasurementMatrix(DrModelKind kind);
// (14). Throws std::invalid_argument for no segments or a non-positive wheelbase.
Eigen::MatrixXd totalObservabilityMatrix(DrModelKind kind, const std::vector<DrSegment>& segments);

struct ObservabilityReport {
  int states = 0;
  int rank = 0;
  std::vector<double> singular_values;  // of the column-normalised TOM, descending
  double tolerance = 0.0;               // singular values below this count as zero
  // Null-space basis, one column per unobservable direction, in reduced row-echelon form
  // (each column has a 1 at its own pivot state and 0 at the other columns' pivots), so the
  // directions read directly: e.g. S_R = S_L = 1, dD = D.
  Eigen::MatrixXd null_space;
};

// Rank by SVD of the TOM with columns scaled to unit norm (states have different units), with
// relative tolerance `relative_tolerance` * largest singular value. Throws std::invalid_argument
// for a tolerance outside (0, 1) or as totalObservabilityMatrix.
ObservabilityReport analyseObservability(DrModelKind kind, const std::vector<DrSegment>& segments,
                                         double relative_tolerance = 1e-9);

// Human-readable report (rank, singular values, null-space columns with state names).
std::string formatReport(DrModelKind kind, const ObservabilityReport& report);

}  // namespace irgs
