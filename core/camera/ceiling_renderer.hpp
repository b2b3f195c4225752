#pragma once
// Renders what the ceiling camera sees: the ceiling plane (tiles, markers, lights, painted
// decorations) through the pinhole camera, with lighting variation, optics blur and sensor noise.
// Deterministic: the same inputs and seed give the same bytes on every run.
//
// Shading: pixel = 255 * albedo * exposure * (ambient + glow near lights) * vignetting, lights
// emit `light_radiance` (above 1: they saturate as real tubes do), rays that miss the ceiling see
// a dark wall. Each pixel averages supersample^2 rays (anti-aliasing), then a Gaussian blur of
// blur_sigma_px, then zero-mean Gaussian noise of noise_sigma grey levels per channel.

#include <cstdint>

#include "core/camera/camera_model.hpp"
#include "core/camera/ceiling_scene.hpp"
#include "core/camera/image.hpp"

namespace irgs {

struct RenderSettings {
  double exposure = 1.0;       // global gain (lighting variation: 0.7 dim .. 1.2 bright)
  double ambient = 0.95;       // illumination away from the lights
  double glow = 0.12;          // extra illumination next to a light
  double glow_radius_m = 0.6;  // e-folding distance of the glow
  double vignetting = 0.15;    // relative darkening in the image corners
  double light_radiance = 2.0;
  Albedo wall{0.30, 0.29, 0.27};  // seen where a ray misses the ceiling
  int supersample = 2;            // rays per pixel along each axis
  double blur_sigma_px = 0.7;     // 0: no blur
  double noise_sigma = 3.0;       // grey levels; 0: no noise
  std::uint64_t seed = 1;
};

// The frame of a camera whose view is `view` (body frame) on a robot at `robot_pose` (world).
// The scene's ceiling height is not used: `view` carries the height.
RgbImage renderCeiling(const CeilingView& view, const CeilingScene& scene, const Pose2& robot_pose,
                       const RenderSettings& settings);

}  // namespace irgs
