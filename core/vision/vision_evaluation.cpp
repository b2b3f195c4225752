#include "core/vision/vision_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/camera/camera_model.hpp"
#include "core/vision/ceiling_vision.hpp"
#include "core/vision/image_convert.hpp"
#include "core/vision/top_view.hpp"

namespace irgs::vision {
namespace {

constexpr double kCeilingM = 2.6;

class Stats {
 public:
  void add(double e) {
    ++count_;
    sum_ += e;
    sum2_ += e * e;
    max_ = std::max(max_, e);
  }
  ErrorStats result(int expected) const {
    ErrorStats s;
    s.count = count_;
    s.expected = expected;
    if (count_ > 0) {
      s.mean_m = sum_ / count_;
      s.rms_m = std::sqrt(sum2_ / count_);
      s.max_m = max_;
    }
    return s;
  }

 private:
  int count_ = 0;
  double sum_ = 0.0, sum2_ = 0.0, max_ = 0.0;
};

CeilingView viewAt(const CeilingCameraConfig& camera, double tilt_rad) {
  return CeilingView(camera.intrinsics, camera.mount, camera.ceilingHeight(kCeilingM), tilt_rad);
}

// A rectangle lies wholly in the image (with a margin) and in the top view.
bool fullyVisible(const CeilingRect& body_rect, const CeilingView& view,
                  const TopViewGeometry& geometry, double margin_px) {
  for (const Vec2& c : body_rect.corners()) {
    const auto px = view.project(c);
    if (!px || !view.inImage(*px, margin_px))
      return false;
    const Vec2 t = geometry.bodyToPixel(c);
    if (t.x() < 1.0 || t.y() < 1.0 || t.x() > geometry.width() - 2.0 ||
        t.y() > geometry.height() - 2.0)
      return false;
  }
  return true;
}

double horizontalRange(const Vec2& body_point, const CameraMount& mount) {
  return std::hypot(body_point.x() - mount.x_m, body_point.y() - mount.y_m);
}

// A uniformly random point of the top view that lies within `range_m` of the camera and far
// enough from the view's edges for a `clearance_m` object; nothing after many misses.
std::optional<Vec2> randomPointInView(std::mt19937_64& rng, const CeilingView& view,
                                      const TopViewGeometry& geometry, double range_m,
                                      double clearance_m) {
  std::uniform_real_distribution<double> ux(geometry.xNearM(), geometry.xFarM());
  std::uniform_real_distribution<double> uy(geometry.yRightM(), geometry.yLeftM());
  for (int attempt = 0; attempt < 200; ++attempt) {
    const Vec2 p(ux(rng), uy(rng));
    if (horizontalRange(p, view.mount()) > range_m)
      continue;
    const CeilingRect probe{p, 0.0, 2.0 * clearance_m, 2.0 * clearance_m};
    if (fullyVisible(probe, view, geometry, 3.0))
      return p;
  }
  return std::nullopt;
}

RenderSettings defaultRender(std::uint64_t seed) {
  RenderSettings s;
  s.seed = seed;
  return s;
}

}  // namespace

TopViewErrorRow topViewGridError(const CeilingCameraConfig& camera, const VisionConfig& vision,
                                 double tilt_rad, double tilt_error_rad, std::uint64_t seed) {
  TopViewErrorRow row;
  row.tilt_rad = tilt_rad;
  const CeilingView view = viewAt(camera, tilt_rad);
  const TopViewGeometry truth_geometry(view, vision.top_view);
  // The grid: 8 cm dark squares every 0.4 m over the view, robot at the origin.
  CeilingScene scene;
  scene.ceiling_height_m = view.ceilingHeightM();
  scene.tile_size_m = 0.0;
  std::vector<Vec2> points;
  const double step = 0.4, dot = 0.08;
  for (double x = std::ceil(truth_geometry.xNearM() / step) * step; x <= truth_geometry.xFarM();
       x += step)
    for (double y = std::ceil(truth_geometry.yRightM() / step) * step; y <= truth_geometry.yLeftM();
         y += step) {
      const CeilingRect r{Vec2(x, y), 0.0, dot, dot};
      if (horizontalRange(r.centre, camera.mount) > camera.working_range_m ||
          !fullyVisible(r, view, truth_geometry, 3.0))
        continue;
      points.push_back(r.centre);
      scene.decorations.push_back({r, {0.05, 0.05, 0.05}});
    }
  const RgbImage frame = renderCeiling(view, scene, Pose2{}, defaultRender(seed));
  const cv::Mat rgb = asRgbMat(frame);
  cv::Mat valid_frame(rgb.rows, rgb.cols, CV_8U, cv::Scalar(255));

  auto measure = [&](double warp_tilt) {
    const CeilingView warp_view = viewAt(camera, warp_tilt);
    const TopViewGeometry g(warp_view, vision.top_view);
    Stats stats;
    if (g.empty())
      return stats.result(static_cast<int>(points.size()));
    cv::Mat top = g.warp(rgb), grey, dark;
    cv::cvtColor(top, grey, cv::COLOR_RGB2GRAY);
    cv::Mat valid = g.warp(valid_frame, cv::INTER_NEAREST);
    cv::erode(valid, valid, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
    cv::threshold(grey, dark, 60, 255, cv::THRESH_BINARY_INV);
    dark &= valid;
    cv::Mat labels, blob_stats, centroids;
    const int n = cv::connectedComponentsWithStats(dark, labels, blob_stats, centroids, 8, CV_32S);
    std::vector<Vec2> found;
    for (int i = 1; i < n; ++i)
      found.push_back(g.pixelToBody(Vec2(centroids.at<double>(i, 0), centroids.at<double>(i, 1))));
    for (const Vec2& p : points) {
      double best = 1e9;
      for (const Vec2& f : found)
        best = std::min(best, (f - p).norm());
      if (best < 0.5 * step)
        stats.add(best);
    }
    return stats.result(static_cast<int>(points.size()));
  };
  row.exact = measure(tilt_rad);
  row.tilt_off = measure(tilt_rad + tilt_error_rad);
  return row;
}

ErrorStats markerCentreError(const CeilingCameraConfig& camera, const VisionConfig& vision,
                             double tilt_rad, int frames, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const CeilingView view = viewAt(camera, tilt_rad);
  const TopViewGeometry geometry(view, vision.top_view);
  const CeilingVision pipeline(vision);
  std::uniform_real_distribution<double> heading(-kPi, kPi);
  Stats stats;
  int expected = 0;
  for (int f = 0; f < frames; ++f) {
    const auto p =
        randomPointInView(rng, view, geometry, camera.working_range_m, 0.75 * vision.marker.size_m);
    if (!p)
      continue;
    CeilingScene scene;
    scene.ceiling_height_m = view.ceilingHeightM();
    scene.markers.push_back({*p, heading(rng), vision.marker.size_m, vision.marker.size_m});
    ++expected;
    const RgbImage frame = renderCeiling(view, scene, Pose2{}, defaultRender(seed + 1000 + f));
    const CeilingVisionResult r = pipeline.process(frame, view);
    double best = 1e9;
    for (const auto& m : r.markers.markers)
      best = std::min(best, (m.centre_body_m - *p).norm());
    if (best < 0.5 * vision.marker.size_m)
      stats.add(best);
  }
  return stats.result(expected);
}

DetectionStats evaluateDetection(const CeilingCameraConfig& camera, const VisionConfig& vision,
                                 int frames, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };
  auto count = [&](int a, int b) { return a + static_cast<int>(unit(rng) * (b - a + 1) * 0.9999); };
  const CeilingVision pipeline(vision);
  const double size = vision.marker.size_m;
  DetectionStats out;
  Stats marker_err, light_err;
  for (int f = 0; f < frames; ++f) {
    const double tilt = uniform(camera.tilt.min_tilt_rad, camera.tilt.max_tilt_rad);
    const CeilingView view = viewAt(camera, tilt);
    const TopViewGeometry geometry(view, vision.top_view);
    const Pose2 pose{uniform(-20.0, 20.0), uniform(-20.0, 20.0), uniform(-kPi, kPi)};
    // The scene, placed in the body frame where the camera looks, stored in the world frame.
    CeilingScene scene;
    scene.ceiling_height_m = view.ceilingHeightM();
    std::vector<std::pair<Vec2, double>> placed;  // body centre, clearance
    auto place = [&](double range, double clearance) -> std::optional<Vec2> {
      for (int attempt = 0; attempt < 20; ++attempt) {
        const auto p = randomPointInView(rng, view, geometry, range, 0.5 * clearance);
        if (!p)
          return std::nullopt;
        bool clear = true;
        for (const auto& [q, c] : placed)
          clear = clear && (q - *p).norm() > 0.5 * (c + clearance) + 0.1;
        if (clear) {
          placed.emplace_back(*p, clearance);
          return p;
        }
      }
      return std::nullopt;
    };
    std::vector<CeilingRect> markers_body;
    // Lights first (they are long), then markers within the working range, then distractors.
    std::vector<CeilingRect> lights_body;
    for (int i = 0, n = count(1, 3); i < n; ++i) {
      const bool panel = unit(rng) < 0.3;
      const double length = panel ? uniform(0.5, 0.6) : uniform(0.9, 1.25);
      const double width = panel ? uniform(0.5, 0.6) : uniform(0.08, 0.14);
      // A light may reach out of the view: placed by its centre with a small clearance.
      if (const auto p = place(vision.top_view.max_range_m, panel ? 0.8 : 1.3))
        lights_body.push_back({*p, uniform(-kPi, kPi), length, width});
    }
    for (int i = 0, n = count(1, 3); i < n; ++i)
      if (const auto p = place(vision.top_view.max_range_m, 1.5 * size))
        markers_body.push_back({*p, uniform(-kPi, kPi), size, size});
    std::vector<PaintedRect> decor_body;
    for (int i = 0, n = count(0, 2); i < n; ++i) {
      const double kind = unit(rng);
      PaintedRect d;
      if (kind < 0.4) {  // a red exit sign: red, but not square
        d.rect.length_m = uniform(0.4, 0.5);
        d.rect.width_m = uniform(0.12, 0.16);
        d.albedo = {0.85, 0.12, 0.12};
      } else if (kind < 0.7) {  // a marker-sized square of another colour
        d.rect.length_m = d.rect.width_m = size;
        d.albedo = unit(rng) < 0.5 ? Albedo{0.9, 0.82, 0.2} : Albedo{0.2, 0.35, 0.8};
      } else {  // a red square twice the marker's size
        d.rect.length_m = d.rect.width_m = 2.0 * size;
        d.albedo = kMarkerRed;
      }
      if (const auto p =
              place(vision.top_view.max_range_m, std::hypot(d.rect.length_m, d.rect.width_m))) {
        d.rect.centre = *p;
        d.rect.heading_rad = uniform(-kPi, kPi);
        decor_body.push_back(d);
      }
    }
    auto toWorld = [&](CeilingRect r) {
      r.centre = pose.toWorld(r.centre);
      r.heading_rad += pose.theta;
      return r;
    };
    for (const auto& m : markers_body)
      scene.markers.push_back(toWorld(m));
    for (const auto& l : lights_body)
      scene.lights.push_back(toWorld(l));
    for (const auto& d : decor_body)
      scene.decorations.push_back({toWorld(d.rect), d.albedo});

    RenderSettings render;
    render.seed = seed * 7919 + static_cast<std::uint64_t>(f);
    render.exposure = uniform(0.7, 1.2);
    render.blur_sigma_px = uniform(0.4, 1.2);
    render.noise_sigma = uniform(1.0, 6.0);
    render.vignetting = uniform(0.0, 0.3);
    const RgbImage frame = renderCeiling(view, scene, pose, render);
    const CeilingVisionResult r = pipeline.process(frame, view);
    ++out.frames;

    // Markers: recall within the working range, precision against every real marker.
    auto found = [&](const CeilingRect& m) {
      double best = 1e9;
      for (const auto& d : r.markers.markers)
        best = std::min(best, (d.centre_body_m - m.centre).norm());
      return best;
    };
    for (const auto& m : markers_body) {
      if (!fullyVisible(m, view, r.geometry, 2.0))
        continue;
      const auto band = static_cast<std::size_t>(horizontalRange(m.centre, camera.mount));
      if (band < out.band_markers.size()) {
        ++out.band_markers[band];
        out.band_found[band] += found(m) < 0.5 * size;
      }
    }
    for (const auto& m : markers_body) {
      if (horizontalRange(m.centre, camera.mount) > camera.working_range_m ||
          !fullyVisible(m, view, r.geometry, 2.0))
        continue;
      ++out.markers_in_range;
      double best = 1e9;
      for (const auto& d : r.markers.markers)
        best = std::min(best, (d.centre_body_m - m.centre).norm());
      if (best < 0.5 * size) {
        ++out.markers_in_range_found;
        marker_err.add(best);
      }
    }
    for (const auto& d : r.markers.markers) {
      ++out.detections;
      for (const auto& m : markers_body)
        if ((d.centre_body_m - m.centre).norm() < 0.5 * size) {
          ++out.detections_true;
          break;
        }
    }
    // Lights: centre error of the lights wholly in view.
    for (const auto& l : lights_body) {
      if (!fullyVisible(l, view, r.geometry, 2.0))
        continue;
      ++out.lights_visible;
      double best = 1e9;
      for (const auto& d : r.lights)
        best = std::min(best, (d.light.centre_body_m - l.centre).norm());
      if (best < 0.3) {
        ++out.lights_found;
        light_err.add(best);
      }
    }
  }
  out.marker_centre = marker_err.result(out.markers_in_range);
  out.light_centre = light_err.result(out.lights_visible);
  return out;
}

}  // namespace irgs::vision
