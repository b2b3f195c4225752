#include "core/estimation/stereo_echo_sim.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/geometry/geometry_queries.hpp"

namespace irgs {

namespace {

// Endpoints closer than this (m) are the same map point (corner adjacency, skipped occluders).
constexpr double kSamePoint_m = 1e-6;
// Legs are shortened by this much at both ends so the reflecting surface itself never occludes.
constexpr double kLegTrim_m = 1e-6;

bool nonNegativeFinite(double v) {
  return std::isfinite(v) && v >= 0.0;
}

bool inBeam(double bearing_rad, double half_angle_rad) {
  return std::abs(wrapAngle(bearing_rad)) <= half_angle_rad;
}

// Parameter of p's projection onto the segment, 0 at a and 1 at b.
double projectionParameter(const Segment& seg, const Vec2& p) {
  const Vec2 ab = seg.b - seg.a;
  return (p - seg.a).dot(ab) / ab.squaredNorm();
}

}  // namespace

StereoEchoSimulator::StereoEchoSimulator(const WorldMap& map, StereoSonarParams params,
                                         StereoEchoNoise noise)
    : params_(params), noise_(noise) {
  validate(params_);
  if (!nonNegativeFinite(noise_.path_stddev_m) || !nonNegativeFinite(noise_.path_stddev_per_m))
    throw std::invalid_argument("StereoEchoNoise: path stddevs must be >= 0 and finite");
  if (!(noise_.dropout_probability >= 0.0 && noise_.dropout_probability <= 1.0))
    throw std::invalid_argument("StereoEchoNoise: dropout_probability must be in [0, 1]");
  if (!(noise_.beam_half_angle_rad > 0.0 && noise_.beam_half_angle_rad <= kPi))
    throw std::invalid_argument("StereoEchoNoise: beam_half_angle_rad must be in (0, pi]");
  if (!nonNegativeFinite(noise_.min_range_m))
    throw std::invalid_argument("StereoEchoNoise: min_range_m must be >= 0 and finite");

  auto add = [this](const Vec2& a, const Vec2& b, const std::string& id) {
    if ((b - a).norm() > kSamePoint_m)
      segments_.push_back({{a, b}, id});
  };
  for (const WorldMap::LabelledSegment& piece : map.labelledSegments())
    add(piece.segment.a, piece.segment.b, piece.id);
  for (const PointFeature& f : map.features) {
    Feature feature{f.kind, f.position, f.id, {}};
    if (f.kind == PointFeatureKind::kCorner) {
      for (const ReflectingSegment& rs : segments_) {
        if ((rs.segment.a - f.position).norm() < kSamePoint_m)
          feature.arms.push_back((rs.segment.b - rs.segment.a).normalized());
        else if ((rs.segment.b - f.position).norm() < kSamePoint_m)
          feature.arms.push_back((rs.segment.a - rs.segment.b).normalized());
      }
    }
    features_.push_back(std::move(feature));
  }
}

bool StereoEchoSimulator::pathClear(const Vec2& from, const Vec2& to, std::size_t skip_segment,
                                    const Vec2* skip_point) const {
  const Vec2 delta = to - from;
  const double length = delta.norm();
  if (length <= 2.0 * kLegTrim_m)
    return true;
  const Vec2 u = delta / length;
  const Vec2 a = from + kLegTrim_m * u;
  const Vec2 b = to - kLegTrim_m * u;
  for (std::size_t j = 0; j < segments_.size(); ++j) {
    if (j == skip_segment)
      continue;
    const Segment& seg = segments_[j].segment;
    if (skip_point != nullptr && ((seg.a - *skip_point).norm() < kSamePoint_m ||
                                  (seg.b - *skip_point).norm() < kSamePoint_m))
      continue;
    if (segmentsIntersect(a, b, seg.a, seg.b))
      return false;
  }
  return true;
}

SimulatedEcho StereoEchoSimulator::idealEcho(const Pose2& sensor) const {
  const double s = params_.half_baseline_m;
  const Vec2 t = sensor.position();
  const Vec2 receivers[2] = {receiver1Position(sensor, s), receiver2Position(sensor, s)};
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  SimulatedEcho best;
  double best_sum = std::numeric_limits<double>::infinity();
  auto consider = [&](const EchoPaths& paths, ReflectorKind kind, std::size_t index,
                      const std::string& id) {
    const double sum = paths.r1_m + paths.r2_m;
    if (sum < best_sum) {
      best_sum = sum;
      best.true_paths = paths;
      best.paths = paths;
      best.kind = kind;
      best.reflector_index = index;
      best.reflector_id = id;
    }
  };

  // Walls: specular reflection via the mirror image of T.
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Segment& seg = segments_[k].segment;
    if (cross(seg.b - seg.a, t - seg.a) == 0.0)
      continue;  // on the wall's line: no face in front
    const WallLine wall = wallLineFacing(seg, t);
    const double d = predictedWallDistance(wall, sensor);
    if (!(d >= noise_.min_range_m) ||
        !inBeam(predictedWallBearing(wall, sensor), noise_.beam_half_angle_rad))
      continue;
    const FacingLine f = robotFacing(wall);
    const Vec2 n(std::cos(f.phi_eff_rad), std::sin(f.phi_eff_rad));
    const Vec2 image = t + 2.0 * d * n;
    bool ok = true;
    for (const Vec2& r : receivers) {
      // Reflection point: where image -> receiver crosses the wall line n . p = p_eff.
      const double h_image = n.dot(image) - f.p_eff_m;  // = d > 0
      const double h_receiver = n.dot(r) - f.p_eff_m;   // < 0 when in front of the face
      if (!(h_receiver < 0.0)) {
        ok = false;
        break;
      }
      const Vec2 hit = image + (h_image / (h_image - h_receiver)) * (r - image);
      const double u = projectionParameter(seg, hit);
      if (u < 0.0 || u > 1.0 || !pathClear(t, hit, k, nullptr) || !pathClear(hit, r, k, nullptr)) {
        ok = false;
        break;
      }
    }
    if (ok)
      consider(wallEchoPaths(wall, sensor, s), ReflectorKind::kWall, k, segments_[k].wall_id);
  }

  // Corners (retro-reflection) and edges (diffraction).
  for (std::size_t i = 0; i < features_.size(); ++i) {
    const Feature& f = features_[i];
    const Vec2 v = t - f.position;
    if (!(v.norm() >= noise_.min_range_m) ||
        !inBeam(predictedPointBearing(f.position, sensor), noise_.beam_half_angle_rad))
      continue;
    if (!pathClear(t, f.position, kNone, &f.position))
      continue;
    if (f.kind == PointFeatureKind::kCorner) {
      if (f.arms.size() == 2) {
        // Inside the opening between the two arms (the side where they span less than pi).
        const double span = cross(f.arms[0], f.arms[1]);
        if (span == 0.0 || cross(f.arms[0], v) * span <= 0.0 || cross(v, f.arms[1]) * span <= 0.0)
          continue;
      }
      consider(cornerEchoPaths(f.position, sensor, s), ReflectorKind::kCorner, i, f.id);
    } else {
      if (!pathClear(f.position, receivers[0], kNone, &f.position) ||
          !pathClear(f.position, receivers[1], kNone, &f.position))
        continue;
      consider(edgeEchoPaths(f.position, sensor, s), ReflectorKind::kEdge, i, f.id);
    }
  }

  if (!std::isfinite(best_sum)) {
    best.status = EchoStatus::kNoReflector;
    return best;
  }
  best.status =
      withinMaxTof(best.true_paths, params_) ? EchoStatus::kEcho : EchoStatus::kBeyondMaxTof;
  return best;
}

SimulatedEcho StereoEchoSimulator::echo(const Pose2& sensor, SimRandom& rng) const {
  if (!std::isfinite(sensor.x) || !std::isfinite(sensor.y) || !std::isfinite(sensor.theta))
    throw std::invalid_argument("StereoEchoSimulator::echo: non-finite sensor pose");
  SimulatedEcho out = idealEcho(sensor);
  // Always three draws, so the random stream does not depend on what was in view.
  const double u = rng.uniform();
  const double g1 = rng.gaussian();
  const double g2 = rng.gaussian();
  if (out.status != EchoStatus::kEcho)
    return out;
  if (u < noise_.dropout_probability) {
    out.status = EchoStatus::kDropout;
    return out;
  }
  out.paths.r1_m += g1 * (noise_.path_stddev_m + noise_.path_stddev_per_m * out.true_paths.r1_m);
  out.paths.r2_m += g2 * (noise_.path_stddev_m + noise_.path_stddev_per_m * out.true_paths.r2_m);
  if (!withinMaxTof(out.paths, params_))
    out.status = EchoStatus::kBeyondMaxTof;
  return out;
}

}  // namespace irgs
