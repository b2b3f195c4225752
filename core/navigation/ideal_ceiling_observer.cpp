#include "core/navigation/ideal_ceiling_observer.hpp"

#include <cmath>

namespace irgs {

namespace {
constexpr std::uint64_t kObserverStream = 20;
constexpr int kLightSamples = 25;  // points along a tube to find the part in view
}  // namespace

IdealCeilingObserver::IdealCeilingObserver(const WorldMap& map, IdealCameraParams params,
                                           std::uint64_t seed)
    : markers_(map.markers),
      lights_(map.lights),
      ceiling_height_m_(map.ceiling_height_m),
      params_(params),
      rng_(SimRandom::stream(seed, kObserverStream)) {}

bool IdealCeilingObserver::inView(const Pose2& pose, double tilt_rad, const Vec2& ceiling_point,
                                  double& slant_m) const {
  const Vec2 camera = pose.toWorld({params_.mount_x_m, 0.0});
  const Vec2 d = Pose2{camera.x(), camera.y(), pose.theta}.toBody(ceiling_point);
  const double h = ceiling_height_m_ - params_.camera_height_m;
  if (!(h > 0.0))
    return false;
  // Camera axes in the body frame (x fwd, y left, z up): optical axis f, image right r, up u.
  const double c = std::cos(tilt_rad), s = std::sin(tilt_rad);
  const double zc = d.x() * c + h * s;   // along f = (c, 0, s)
  const double xc = -d.y();              // along r = (0, -1, 0)
  const double yc = -d.x() * s + h * c;  // along u = (-s, 0, c)
  slant_m = std::sqrt(d.squaredNorm() + h * h);
  if (!(zc > 0.0))
    return false;
  return std::abs(std::atan2(xc, zc)) <= 0.5 * params_.horizontal_fov_rad &&
         std::abs(std::atan2(yc, zc)) <= 0.5 * params_.vertical_fov_rad;
}

CeilingObservation IdealCeilingObserver::observe(const Pose2& true_pose, double tilt_rad,
                                                 double time_s) {
  CeilingObservation out;
  out.time_s = time_s;
  out.tilt_rad = tilt_rad;
  const auto noisy = [&](const Vec2& p, double slant) {
    const double sd = params_.position_stddev_m + params_.position_stddev_per_m * slant;
    return Vec2(p.x() + sd * rng_.gaussian(), p.y() + sd * rng_.gaussian());
  };
  for (const CeilingMarker& m : markers_) {
    double slant = 0.0;
    if (!inView(true_pose, tilt_rad, m.position, slant) || slant > params_.marker_range_m)
      continue;
    if (!rng_.bernoulli(params_.detection_probability))
      continue;
    MarkerDetection det;
    det.centre_body_m = noisy(true_pose.toBody(m.position), slant);
    det.heading_rad = std::remainder(m.heading_rad - true_pose.theta, 0.5 * kPi);
    out.markers.push_back(det);
  }
  for (const CeilingLight& l : lights_) {
    // The visible stretch of the tube: first and last of evenly spaced points in view.
    int first = -1, last = -1;
    double nearest = 0.0;
    for (int k = 0; k < kLightSamples; ++k) {
      const double u = static_cast<double>(k) / (kLightSamples - 1);
      const Vec2 p = l.tube.a + u * (l.tube.b - l.tube.a);
      double slant = 0.0;
      if (!inView(true_pose, tilt_rad, p, slant) || slant > params_.light_range_m)
        continue;
      if (first < 0) {
        first = k;
        nearest = slant;
      }
      last = k;
      nearest = std::min(nearest, slant);
    }
    if (first < 0 || !rng_.bernoulli(params_.detection_probability))
      continue;
    const Vec2 a =
        l.tube.a + (static_cast<double>(first) / (kLightSamples - 1)) * (l.tube.b - l.tube.a);
    const Vec2 b =
        l.tube.a + (static_cast<double>(last) / (kLightSamples - 1)) * (l.tube.b - l.tube.a);
    LightDetection det;
    const Vec2 ab = true_pose.toBody(b) - true_pose.toBody(a);
    det.centre_body_m = noisy(true_pose.toBody(0.5 * (a + b)), nearest);
    det.axis_rad = std::remainder(std::atan2(ab.y(), ab.x()), kPi);
    det.length_m = (b - a).norm();
    out.lights.push_back(det);
  }
  return out;
}

}  // namespace irgs
