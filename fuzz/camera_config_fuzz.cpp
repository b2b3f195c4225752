// libFuzzer harness for the ceiling-camera JSON sections: a robot profile's "ceiling_camera"
// (core/camera) and the vision pipelines' VisionConfig (core/vision). The first byte picks the
// reader. Invariants: never crash or throw; a config read without errors is usable (the tilt law
// evaluates, the pipelines construct and run on a small frame).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/camera/ceiling_camera_config.hpp"
#include "core/vision/ceiling_vision.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  const nlohmann::json json = nlohmann::json::parse(rest.begin(), rest.end(), nullptr, false);
  if (json.is_discarded())
    return 0;
  if (data[0] & 1U) {
    const irgs::CeilingCameraConfigResult r = irgs::ceilingCameraFromJson(json);
    if (r.errors.empty()) {
      const irgs::CeilingCameraConfig& c = r.config;
      IRGS_FUZZ_CHECK(c.intrinsics.width_px > 0 && c.intrinsics.fx_px > 0.0);
      const double t = c.tilt.tiltFor(1.0);
      IRGS_FUZZ_CHECK(t >= c.tilt.min_tilt_rad - 1e-12 && t <= c.tilt.max_tilt_rad + 1e-12);
    }
  } else {
    const irgs::vision::VisionConfigResult r = irgs::vision::visionConfigFromJson(json);
    if (r.errors.empty()) {
      // A small camera so each input stays fast; the pipelines must accept any valid config.
      irgs::CameraIntrinsics small{64, 48, 55.4, 55.4, 31.5, 23.5, 0.0};
      const irgs::CeilingView view(small, irgs::CameraMount{}, 2.5, 1.2);
      irgs::vision::VisionConfig config = r.config;
      config.top_view.px_per_m = std::min(config.top_view.px_per_m, 50.0);
      const irgs::vision::CeilingVision vision(config);
      const irgs::vision::CeilingVisionResult out = vision.process(irgs::RgbImage(64, 48), view);
      IRGS_FUZZ_CHECK(out.markers.markers.empty());
    }
  }
  return 0;
}
