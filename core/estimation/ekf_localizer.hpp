#pragma once
// EKF localization of paper 000 (digest 1.5-1.7): pose U = (x, y, Phi) predicted from odometry
// (differential drive, or the three-caster robot with least-squares J+ and adaptive process
// noise), corrected by stereo-sonar (d, theta) readings matched against a known map of walls,
// corners and edges, one scalar measurement at a time (d first, then theta for walls).
//
// Numerics: Joseph-form covariance update, wrapped angle innovations, Mahalanobis gate,
// symmetric P after every step; non-finite inputs are rejected and leave the filter unchanged.

#include <array>
#include <cstddef>
#include <limits>
#include <string>

#include "core/estimation/caster_odometry.hpp"
#include "core/estimation/localization_map.hpp"
#include "core/estimation/localization_types.hpp"
#include "core/estimation/stereo_sonar.hpp"

namespace irgs {

struct EkfLocalizerConfig {
  double eps1_m = 0.1;               // (41) corner/edge match radius [000: 0.1 m]
  double eps2_rad = degToRad(10.0);  // (42) wall angle match window [000: 10 deg]
  // (49) Mahalanobis gate g on v^2 / S per scalar update [000: infinity, all matches accepted].
  double gate = std::numeric_limits<double>::infinity();
  double r_d_m2 = 0.01 * 0.01;                          // R_d, not given in 000
  double r_theta_rad2 = degToRad(2.0) * degToRad(2.0);  // R_theta, not given in 000
  bool use_bearing = true;                              // update with theta for walls (16)/(47)
  bool use_edge_inverse = true;  // re-invert a reading matched to an edge with the edge model
};

// Throws std::invalid_argument for negative/NaN windows or gate, or non-positive R.
void validate(const EkfLocalizerConfig& config);

// Process noise of the differential-drive prediction: each wheel's travel error has variance
// wheel_variance_per_m * |travel| (m^2), plus a constant per-step term in world (x, y, Phi).
struct DiffDriveNoise {
  double wheel_variance_per_m = 1e-4;
  LocCov per_step = LocCov::Zero();
};

struct StereoSensor {
  SensorMount mount;
  double half_baseline_m = 0.2;  // s
};

// kRejectedNonFinite: NaN/Inf or otherwise invalid input (wheelbase <= 0, negative lambda or
// noise); kRejectedCasterSingular: the caster steering makes G rank deficient. Both leave the
// filter unchanged.
enum class PredictStatus { kApplied, kRejectedNonFinite, kRejectedCasterSingular };

struct CasterPrediction {
  PredictStatus status = PredictStatus::kRejectedNonFinite;
  double residual_norm = 0.0;  // ||e||_2 of (35)
};

enum class UpdateStatus {
  kUpdated,            // at least one scalar update was applied
  kRejectedNonFinite,  // NaN/Inf in the reading
  kInvalidEcho,        // (5)/(6) validity checks failed (first-stage error handling)
  kNoMatch,            // no corner/edge within eps1 and no wall within eps2 (second stage)
  kGated,              // matched, but every scalar failed the gate (49)
};
enum class MatchKind { kNone, kWall, kCorner, kEdge };

struct ScalarUpdate {
  bool attempted = false;
  bool applied = false;  // false when gated out
  double measured = 0.0;
  double predicted = 0.0;
  double innovation = 0.0;  // (48) V = Z - Z^ (wrapped for theta)
  double s = 0.0;           // (44)/(45) innovation variance
  double nis = 0.0;         // V^2 / S, compared with the gate g (49)
};

struct LocalizationUpdate {
  UpdateStatus status = UpdateStatus::kRejectedNonFinite;
  InversionStatus inversion = InversionStatus::kNonFinite;
  MatchKind match = MatchKind::kNone;
  std::size_t feature_index = 0;  // into LocalizationMap::walls or ::points
  std::string feature_id;
  double match_metric = 0.0;  // m1 (41) for points, m2 (43) for walls
  double measured_d_m = 0.0;  // from (5), or the edge inverse for an edge match
  double measured_theta_rad = 0.0;
  ScalarUpdate distance;
  ScalarUpdate bearing;
};

const char* toString(UpdateStatus status);
const char* toString(MatchKind kind);

class EkfLocalizer {
 public:
  // Throws std::invalid_argument for a non-finite state or covariance, a P that is not symmetric
  // positive semi-definite, or an invalid config.
  EkfLocalizer(const LocState& x0, const LocCov& p0, EkfLocalizerConfig config = {});

  void reset(const LocState& x0, const LocCov& p0);

  // Differential drive: wheel travels over the period (m) and the wheel separation (m).
  // Midpoint arc model; P = F P F' + G Qw G' + Q_step.
  PredictStatus predictDiffDrive(double left_m, double right_m, double wheelbase_m,
                                 const DiffDriveNoise& noise);
  // Generic body-frame increment (dx forward, dy left, dPhi) with its covariance in the body frame.
  PredictStatus predictBodyIncrement(const BodyTwist& body_delta, const LocCov& body_cov);
  // Three-caster robot (34)-(37): DeltaTheta = six encoder increments (rad) over the period,
  // steering angles at the period; Q = lambda ||e|| I6 (36), P += J+ Q J+' (37, A000-4).
  CasterPrediction predictCaster(const CasterDriveGeometry& geometry,
                                 const std::array<double, 3>& steering_rad,
                                 const CasterVector& delta_theta, double lambda = 0.005);
  // Same from an already computed least-squares odometry (e.g. casterIntervalOdometry):
  // U += R(Phi) body_delta, P += lambda ||e|| R G+ G+' R'. Rejected when !odometry.ok.
  CasterPrediction predictCaster(const CasterOdometry& odometry, double lambda);

  // One stereo reading (path lengths r1 to R1, r2 to R2): invert (5)-(8), match, update.
  LocalizationUpdate update(const EchoPaths& reading, const StereoSensor& sensor,
                            const LocalizationMap& map);
  // Same from an already inverted (d, theta) (no edge re-inversion possible).
  LocalizationUpdate updateWithDistanceBearing(double d_m, double theta_rad,
                                               const SensorMount& mount,
                                               const LocalizationMap& map);

  const LocState& state() const { return x_; }
  const LocCov& covariance() const { return p_; }
  Pose2 pose() const { return toPose(x_); }
  const EkfLocalizerConfig& config() const { return config_; }

 private:
  LocalizationUpdate matchAndUpdate(LocalizationUpdate result, const EchoPaths* reading,
                                    const StereoSensor& sensor, const LocalizationMap& map);
  ScalarUpdate scalarUpdate(double measured, double predicted, const LocRow& h, double r,
                            bool is_angle);
  void propagate(const LocState& x_new, const LocCov& f, const LocCov& q);

  LocState x_;
  LocCov p_;
  EkfLocalizerConfig config_;
};

}  // namespace irgs
