#include "core/camera/ceiling_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace irgs {
namespace {

struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};

// A rectangle with its orientation's sine and cosine computed once (the per-ray tests are the
// renderer's inner loop).
struct PreparedRect {
  Vec2 centre;
  double c, s, half_length, half_width;
  Albedo albedo;

  explicit PreparedRect(const CeilingRect& r, Albedo a = {})
      : centre(r.centre),
        c(std::cos(r.heading_rad)),
        s(std::sin(r.heading_rad)),
        half_length(0.5 * r.length_m),
        half_width(0.5 * r.width_m),
        albedo(a) {}
  bool contains(const Vec2& p) const {
    const double dx = p.x() - centre.x(), dy = p.y() - centre.y();
    return std::abs(c * dx + s * dy) <= half_length && std::abs(-s * dx + c * dy) <= half_width;
  }
  double distance(const Vec2& p) const {
    const double dx = p.x() - centre.x(), dy = p.y() - centre.y();
    const double ex = std::max(std::abs(c * dx + s * dy) - half_length, 0.0);
    const double ey = std::max(std::abs(-s * dx + c * dy) - half_width, 0.0);
    return std::hypot(ex, ey);
  }
};

// The scene in the robot's body frame, only what can matter for this frame.
struct BodyScene {
  std::vector<PreparedRect> markers;
  std::vector<PreparedRect> lights;
  std::vector<PreparedRect> decorations;
};

CeilingRect toBody(const CeilingRect& r, const Pose2& pose) {
  CeilingRect b = r;
  b.centre = pose.toBody(r.centre);
  b.heading_rad = r.heading_rad - pose.theta;
  return b;
}

// The body-frame bounding box of the ceiling the image can show: the image border's rays on the
// ceiling, a ray that misses it (or lands farther than `reach_m`) taken out to `reach_m`.
struct Box {
  Vec2 lo{1e300, 1e300};
  Vec2 hi{-1e300, -1e300};
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Whether a disc of radius r at c can touch the box.
  bool touches(const Vec2& c, double r) const {
    return c.x() + r >= lo.x() && c.x() - r <= hi.x() && c.y() + r >= lo.y() && c.y() - r <= hi.y();
  }
};

Box footprint(const CeilingView& view, double reach_m) {
  Box box;
  const Vec2 mount(view.mount().x_m, view.mount().y_m);
  const int w = view.intrinsics().width_px, h = view.intrinsics().height_px;
  auto add = [&](double u, double v) {
    const Eigen::Vector3d d = view.rayBody(Vec2(u, v));
    const Vec2 horizontal(d.x(), d.y());
    const double hn = horizontal.norm();
    Vec2 p = mount;
    if (d.z() > 1e-9 && view.heightAboveCameraM() / d.z() * hn <= reach_m)
      p += view.heightAboveCameraM() / d.z() * horizontal;
    else if (hn > 1e-12)
      p += reach_m / hn * horizontal;
    box.add(p);
  };
  constexpr int kSteps = 16;
  for (int i = 0; i <= kSteps; ++i) {
    const double u = -0.5 + w * static_cast<double>(i) / kSteps;
    const double v = -0.5 + h * static_cast<double>(i) / kSteps;
    add(u, -0.5);
    add(u, h - 0.5);
    add(-0.5, v);
    add(w - 0.5, v);
  }
  box.add(mount);
  return box;
}

// Everything that can show in the frame (rectangles are tested by their circumradius; lights
// by their glow's reach as well).
BodyScene bodyScene(const CeilingScene& scene, const Pose2& pose, const Box& box,
                    double light_margin_m) {
  BodyScene out;
  auto visible = [&](const CeilingRect& body, double margin) {
    return box.touches(body.centre, 0.5 * std::hypot(body.length_m, body.width_m) + margin);
  };
  for (const auto& m : scene.markers)
    if (const CeilingRect b = toBody(m, pose); visible(b, 0.0))
      out.markers.emplace_back(b);
  for (const auto& l : scene.lights)
    if (const CeilingRect b = toBody(l, pose); visible(b, light_margin_m))
      out.lights.emplace_back(b);
  for (const auto& d : scene.decorations)
    if (const CeilingRect b = toBody(d.rect, pose); visible(b, 0.0))
      out.decorations.emplace_back(b, d.albedo);
  return out;
}

// Reflectance at body point p on the ceiling, or nothing for a light (which emits instead).
std::optional<Albedo> albedoAt(const Vec2& p, const Vec2& p_world, const CeilingScene& scene,
                               const BodyScene& body) {
  // A paper marker stuck where a lamp is covers the lamp (maps put markers on light rows).
  for (const auto& m : body.markers)
    if (m.contains(p))
      return kMarkerRed;
  for (const auto& l : body.lights)
    if (l.contains(p))
      return std::nullopt;
  for (const auto& d : body.decorations)
    if (d.contains(p))
      return d.albedo;
  Albedo a = scene.ceiling;
  if (scene.tile_size_m > 0.0) {
    // Seams of the ceiling tiles: 1 cm darker lines on a world-fixed grid.
    const double seam = 0.01;
    const double fx = std::abs(std::remainder(p_world.x(), scene.tile_size_m));
    const double fy = std::abs(std::remainder(p_world.y(), scene.tile_size_m));
    if (fx < 0.5 * seam || fy < 0.5 * seam) {
      a.r *= 0.8;
      a.g *= 0.8;
      a.b *= 0.8;
    }
  }
  return a;
}

std::vector<double> gaussianKernel(double sigma) {
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> k(static_cast<std::size_t>(2 * radius + 1));
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    const double v = std::exp(-0.5 * i * i / (sigma * sigma));
    k[static_cast<std::size_t>(i + radius)] = v;
    sum += v;
  }
  for (double& v : k)
    v /= sum;
  return k;
}

// Separable Gaussian blur of a float RGB buffer, borders replicated.
void blur(std::vector<Rgb>& img, int w, int h, double sigma) {
  const std::vector<double> k = gaussianKernel(sigma);
  const int r = static_cast<int>(k.size() / 2);
  std::vector<Rgb> tmp(img.size());
  auto idx = [w](int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Rgb s;
      for (int i = -r; i <= r; ++i) {
        const Rgb& p = img[idx(std::clamp(x + i, 0, w - 1), y)];
        const double kv = k[static_cast<std::size_t>(i + r)];
        s.r += kv * p.r;
        s.g += kv * p.g;
        s.b += kv * p.b;
      }
      tmp[idx(x, y)] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Rgb s;
      for (int i = -r; i <= r; ++i) {
        const Rgb& p = tmp[idx(x, std::clamp(y + i, 0, h - 1))];
        const double kv = k[static_cast<std::size_t>(i + r)];
        s.r += kv * p.r;
        s.g += kv * p.g;
        s.b += kv * p.b;
      }
      img[idx(x, y)] = s;
    }
}

// Standard normal deviates from a fixed generator: Box-Muller on mt19937_64, so the numbers do
// not depend on the standard library's distribution implementation.
class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : rng_(seed) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(rng_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
    const double rad = std::sqrt(-2.0 * std::log(u1));
    spare_ = rad * std::sin(2.0 * kPi * u2);
    has_spare_ = true;
    return rad * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace

RgbImage renderCeiling(const CeilingView& view, const CeilingScene& scene, const Pose2& robot_pose,
                       const RenderSettings& s) {
  const int w = view.intrinsics().width_px, h = view.intrinsics().height_px;
  const int ss = std::max(1, s.supersample);
  // Only what the frame can show: grazing rays are cut at 60 m (at 35 deg with a 60 deg field
  // of view the image reaches about 10 m of a normal ceiling); glow counts within 5 radii.
  const BodyScene body = bodyScene(scene, robot_pose, footprint(view, 60.0), 5.0 * s.glow_radius_m);
  const double hc = view.heightAboveCameraM();
  const double cx = view.intrinsics().cx_px, cy = view.intrinsics().cy_px;
  const double corner2 = cx * cx + cy * cy;
  const double pc = std::cos(robot_pose.theta), ps = std::sin(robot_pose.theta);

  // The glow varies slowly: computed every kGlowStep pixels, interpolated bilinearly between.
  constexpr int kGlowStep = 4;
  const int gw = w / kGlowStep + 2, gh = h / kGlowStep + 2;
  std::vector<double> glow_grid(static_cast<std::size_t>(gw) * static_cast<std::size_t>(gh), 0.0);
  if (!body.lights.empty()) {
    for (int j = 0; j < gh; ++j)
      for (int i = 0; i < gw; ++i)
        if (const auto c = view.backProject(Vec2(i * kGlowStep, j * kGlowStep))) {
          double g = 0.0;
          for (const auto& l : body.lights)
            g = std::max(g, std::exp(-l.distance(*c) / s.glow_radius_m));
          glow_grid[static_cast<std::size_t>(j * gw + i)] = g;
        }
  }
  auto glowAt = [&](int u, int v) {
    const int i = u / kGlowStep, j = v / kGlowStep;
    const double fu = static_cast<double>(u - i * kGlowStep) / kGlowStep;
    const double fv = static_cast<double>(v - j * kGlowStep) / kGlowStep;
    auto at = [&](int a, int b) { return glow_grid[static_cast<std::size_t>(b * gw + a)]; };
    return (1 - fv) * ((1 - fu) * at(i, j) + fu * at(i + 1, j)) +
           fv * ((1 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
  };

  std::vector<Rgb> img(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      // Illumination at the pixel centre: ambient, glow from the nearest lights, vignetting.
      const double r2 = ((u - cx) * (u - cx) + (v - cy) * (v - cy)) / corner2;
      const double vignette = 1.0 - s.vignetting * r2;
      const double illum = s.ambient + s.glow * glowAt(u, v);
      const double gain = 255.0 * s.exposure * vignette;
      Rgb sum;
      for (int j = 0; j < ss; ++j) {
        for (int i = 0; i < ss; ++i) {
          const Vec2 px(u + (i + 0.5) / ss - 0.5, v + (j + 0.5) / ss - 0.5);
          const Eigen::Vector3d d = view.rayBody(px);
          if (!(d.z() > 1e-9)) {
            sum.r += gain * s.wall.r;
            sum.g += gain * s.wall.g;
            sum.b += gain * s.wall.b;
            continue;
          }
          const double t = hc / d.z();
          const Vec2 p(view.mount().x_m + t * d.x(), view.mount().y_m + t * d.y());
          const Vec2 p_world(robot_pose.x + pc * p.x() - ps * p.y(),
                             robot_pose.y + ps * p.x() + pc * p.y());
          const auto a = albedoAt(p, p_world, scene, body);
          if (!a) {
            const double e = gain * s.light_radiance;
            sum.r += e;
            sum.g += e;
            sum.b += e * 0.97;  // fluorescent tubes are slightly blue-free white
            continue;
          }
          sum.r += gain * illum * a->r;
          sum.g += gain * illum * a->g;
          sum.b += gain * illum * a->b;
        }
      }
      const double n = 1.0 / (ss * ss);
      // Saturation happens on the sensor, before the optics blur would mix it: clip per ray
      // would be more exact; clipping the pixel average keeps saturated tubes flat-topped.
      img[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)] =
          {std::min(sum.r * n, 300.0), std::min(sum.g * n, 300.0), std::min(sum.b * n, 300.0)};
    }
  }
  if (s.blur_sigma_px > 0.0)
    blur(img, w, h, s.blur_sigma_px);

  RgbImage out(w, h);
  Gaussian noise(s.seed);
  auto quantise = [](double x) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(x), 0L, 255L));
  };
  for (int v = 0; v < h; ++v) {
    std::uint8_t* row = out.row(v);
    for (int u = 0; u < w; ++u) {
      const Rgb& p = img[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) +
                         static_cast<std::size_t>(u)];
      double r = p.r, g = p.g, b = p.b;
      if (s.noise_sigma > 0.0) {
        r += s.noise_sigma * noise.next();
        g += s.noise_sigma * noise.next();
        b += s.noise_sigma * noise.next();
      }
      row[3 * u] = quantise(r);
      row[3 * u + 1] = quantise(g);
      row[3 * u + 2] = quantise(b);
    }
  }
  return out;
}

}  // namespace irgs
