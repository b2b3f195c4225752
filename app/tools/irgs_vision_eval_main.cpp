// irgs-vision-eval: the ceiling camera and vision pipelines of 002_… in the terminal
// (docs/landmark-navigation.md, "Camera and vision").
//   default     (a) top-view metric error of a rendered ceiling grid and the marker detector's
//               centre error against tilt (35, 45, 60, 85, 90 deg); (b) detection on generated
//               frames: marker recall / precision within the working range, light-centre error
//   --image F / --video F / --device D
//               runs the pipelines on real frames (a file or a V4L2 camera) taken at --tilt
//               degrees and prints what each frame shows
//   --check     exit 1 unless recall >= 0.95 and precision >= 0.99 (the acceptance thresholds)
// Exit codes: 0 success, 1 check failed or frames unreadable, 2 usage error.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "core/camera/ceiling_camera_config.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/vision/ceiling_vision.hpp"
#include "core/vision/image_convert.hpp"
#include "core/vision/io/frame_source.hpp"
#include "core/vision/vision_evaluation.hpp"

namespace {

using namespace irgs;
using namespace irgs::vision;

constexpr const char* kUsage =
    "usage: irgs-vision-eval [--frames N] [--per-tilt N] [--seed S] [--check]\n"
    "                        [--profile ROBOT.json] [--vision-config VISION.json]\n"
    "       irgs-vision-eval (--image FILE | --video FILE | --device /dev/videoN) --tilt DEG\n"
    "                        [--ceiling-height M] [--max-frames N] [--save-top-view FILE]\n"
    "                        [--profile ROBOT.json] [--vision-config VISION.json]\n";

struct UsageError {
  std::string message;
};

struct Options {
  int frames = 500;
  int per_tilt = 40;
  std::uint64_t seed = 1;
  bool check = false;
  std::string profile;
  std::string vision_config;
  std::string source;  // --image / --video / --device
  std::optional<double> tilt_deg;
  double ceiling_height_m = 2.6;
  int max_frames = 10;
  std::string save_top_view;
};

double number(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v))
      return v;
  } catch (const std::exception&) {
  }
  throw UsageError{option + ": not a number: '" + text + "'"};
}

int integer(const std::string& option, const std::string& text, int lo, int hi) {
  const double v = number(option, text);
  if (v < lo || v > hi || v != std::floor(v))
    throw UsageError{option + " must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]"};
  return static_cast<int>(v);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc)
        throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "--frames")
      o.frames = integer(a, value(), 1, 100000);
    else if (a == "--per-tilt")
      o.per_tilt = integer(a, value(), 1, 10000);
    else if (a == "--seed")
      o.seed = static_cast<std::uint64_t>(integer(a, value(), 0, 1 << 30));
    else if (a == "--check")
      o.check = true;
    else if (a == "--profile")
      o.profile = value();
    else if (a == "--vision-config")
      o.vision_config = value();
    else if (a == "--image" || a == "--video" || a == "--device")
      o.source = value();
    else if (a == "--tilt")
      o.tilt_deg = number(a, value());
    else if (a == "--ceiling-height")
      o.ceiling_height_m = number(a, value());
    else if (a == "--max-frames")
      o.max_frames = integer(a, value(), 1, 1000000);
    else if (a == "--save-top-view")
      o.save_top_view = value();
    else if (a == "--help" || a == "-h")
      throw UsageError{""};
    else
      throw UsageError{"unknown option " + a};
  }
  if (!o.source.empty() && !o.tilt_deg)
    throw UsageError{
        "real frames need --tilt DEG (the camera-to-ceiling angle they were taken at)"};
  if (o.tilt_deg && (*o.tilt_deg <= 0.0 || *o.tilt_deg > 90.0))
    throw UsageError{"--tilt must be in (0, 90] degrees"};
  return o;
}

CeilingCameraConfig loadCamera(const std::string& path) {
  if (path.empty())
    return {};
  const RobotProfileResult loaded = loadRobotProfileFile(path);
  if (!loaded.profile)
    throw std::runtime_error("cannot load robot profile " + path);
  const auto cam = ceilingCameraFromProfile(*loaded.profile);
  if (!cam.errors.empty())
    throw std::runtime_error(path + ": " + cam.errors.front());
  return cam.config;
}

VisionConfig loadVision(const std::string& path) {
  if (path.empty())
    return {};
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot read " + path);
  const auto r = visionConfigFromJson(nlohmann::json::parse(in));
  if (!r.errors.empty())
    throw std::runtime_error(path + ": " + r.errors.front());
  return r.config;
}

std::string mm(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", 1000.0 * m);
  return buf;
}

int evaluate(const Options& o, const CeilingCameraConfig& camera, const VisionConfig& vision) {
  std::printf(
      "Ceiling camera: %dx%d, fx %.1f px, mount (%.2f, %.2f, %.2f) m, ceiling 2.60 m, "
      "working range %.1f m; top view %.0f px/m\n\n",
      camera.intrinsics.width_px, camera.intrinsics.height_px, camera.intrinsics.fx_px,
      camera.mount.x_m, camera.mount.y_m, camera.mount.z_m, camera.working_range_m,
      vision.top_view.px_per_m);
  std::printf(
      "(a) Top-view metric error of a rendered grid (8 cm squares every 0.4 m within the "
      "working range), and the marker-centre error (%d frames per tilt), in mm\n",
      o.per_tilt);
  std::printf(
      "| tilt | grid points | mean | RMS | max | mean, tilt +1 deg | markers found | "
      "centre mean | centre RMS | centre max |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (double tilt_deg : {35.0, 45.0, 60.0, 85.0, 90.0}) {
    const double tilt = degToRad(tilt_deg);
    const TopViewErrorRow g = topViewGridError(camera, vision, tilt, degToRad(1.0), o.seed);
    const ErrorStats m = markerCentreError(camera, vision, tilt, o.per_tilt, o.seed);
    std::printf("| %.0f | %d/%d | %s | %s | %s | %s | %d/%d | %s | %s | %s |\n", tilt_deg,
                g.exact.count, g.exact.expected, mm(g.exact.mean_m).c_str(),
                mm(g.exact.rms_m).c_str(), mm(g.exact.max_m).c_str(), mm(g.tilt_off.mean_m).c_str(),
                m.count, m.expected, mm(m.mean_m).c_str(), mm(m.rms_m).c_str(),
                mm(m.max_m).c_str());
  }
  const DetectionStats d = evaluateDetection(camera, vision, o.frames, o.seed);
  std::printf(
      "\n(b) Detection on %d generated frames (seed %llu): tilt 35..90 deg, random pose, "
      "exposure 0.7..1.2, blur 0.4..1.2 px, noise 1..6 grey levels, 1-3 markers, 1-3 "
      "lights, 0-2 distractors\n",
      d.frames, static_cast<unsigned long long>(o.seed));
  std::printf("| quantity | value |\n|---|---:|\n");
  std::printf("| markers in working range | %d |\n", d.markers_in_range);
  std::printf("| marker recall | %.4f (%d/%d) |\n", d.recall(), d.markers_in_range_found,
              d.markers_in_range);
  std::printf("| marker precision | %.4f (%d/%d) |\n", d.precision(), d.detections_true,
              d.detections);
  std::printf("| marker-centre error mean / RMS / max, mm | %s / %s / %s |\n",
              mm(d.marker_centre.mean_m).c_str(), mm(d.marker_centre.rms_m).c_str(),
              mm(d.marker_centre.max_m).c_str());
  std::printf("| lights wholly in view, found | %d/%d |\n", d.lights_found, d.lights_visible);
  std::printf("| light-centre error mean / RMS / max, mm | %s / %s / %s |\n",
              mm(d.light_centre.mean_m).c_str(), mm(d.light_centre.rms_m).c_str(),
              mm(d.light_centre.max_m).c_str());
  std::printf(
      "\nMarker recall by horizontal distance from the camera (all tilts; the working "
      "range is %.1f m)\n| distance | markers | found | recall |\n|---|---:|---:|---:|\n",
      camera.working_range_m);
  for (std::size_t b = 0; b < d.band_markers.size(); ++b)
    if (d.band_markers[b] > 0)
      std::printf("| %zu-%zu m | %d | %d | %.3f |\n", b, b + 1, d.band_markers[b], d.band_found[b],
                  static_cast<double>(d.band_found[b]) / d.band_markers[b]);
  if (o.check && (d.recall() < 0.95 || d.precision() < 0.99)) {
    std::fprintf(stderr, "check failed: recall %.4f (>= 0.95), precision %.4f (>= 0.99)\n",
                 d.recall(), d.precision());
    return 1;
  }
  return 0;
}

int realFrames(const Options& o, const CeilingCameraConfig& camera, const VisionConfig& vision) {
  auto opened =
      FrameSource::open(o.source, camera.intrinsics.width_px, camera.intrinsics.height_px);
  if (!opened.source) {
    std::fprintf(stderr, "irgs-vision-eval: %s\n", opened.error.c_str());
    return 1;
  }
  const CeilingVision pipeline(vision);
  int n = 0;
  while (n < o.max_frames) {
    const auto frame = opened.source->next();
    if (!frame)
      break;
    CameraIntrinsics intr = camera.intrinsics;
    if (frame->width != intr.width_px || frame->height != intr.height_px) {
      std::fprintf(stderr, "irgs-vision-eval: frame is %dx%d, the camera profile says %dx%d\n",
                   frame->width, frame->height, intr.width_px, intr.height_px);
      return 1;
    }
    const CeilingView view(intr, camera.mount, camera.ceilingHeight(o.ceiling_height_m),
                           degToRad(*o.tilt_deg));
    const CeilingVisionResult r = pipeline.process(*frame, view);
    std::printf("frame %d: %zu marker(s), %zu light(s)\n", n, r.markers.markers.size(),
                r.lights.size());
    for (const auto& m : r.markers.markers)
      std::printf("  marker at (%.3f, %.3f) m, score %.2f\n", m.centre_body_m.x(),
                  m.centre_body_m.y(), m.score);
    for (const auto& l : r.lights)
      std::printf("  light at (%.3f, %.3f) m, axis %.1f deg, length %.2f m\n",
                  l.light.centre_body_m.x(), l.light.centre_body_m.y(), radToDeg(l.light.axis_rad),
                  l.light.length_m);
    if (!o.save_top_view.empty() && n == 0 && !r.top_view.empty() &&
        !writeImage(o.save_top_view, fromRgbMat(r.top_view)))
      std::fprintf(stderr, "irgs-vision-eval: cannot write %s\n", o.save_top_view.c_str());
    ++n;
  }
  if (n == 0) {
    std::fprintf(stderr, "irgs-vision-eval: %s gave no frame\n", o.source.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const CeilingCameraConfig camera = loadCamera(o.profile);
    const VisionConfig vision = loadVision(o.vision_config);
    return o.source.empty() ? evaluate(o, camera, vision) : realFrames(o, camera, vision);
  } catch (const UsageError& e) {
    if (!e.message.empty())
      std::cerr << "irgs-vision-eval: " << e.message << "\n";
    std::cerr << kUsage;
    return e.message.empty() ? 0 : 2;
  } catch (const std::exception& e) {
    std::cerr << "irgs-vision-eval: " << e.what() << "\n";
    return 1;
  }
}
