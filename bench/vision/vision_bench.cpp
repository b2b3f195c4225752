// Ceiling-vision pipelines against the floor of their cost. Every benchmark processes the same
// 16 rendered 640 x 480 frames in turn (tilts 35..90 deg, a corridor ceiling with markers and
// lights); items/s = frames per second. OpenCV runs single-threaded (cv::setNumThreads(1)) so
// the figures do not depend on how busy the machine's other cores are.
//   Floor        cv::warpPerspective to the top view + cv::cvtColor to YCrCb
//   Marker       top view + the marker pipeline (YCrCb, Cr threshold, morphology, contours,
//                vertices, template matching)
//   Light        top view + the light pipeline (darken, binarise, erode, dilate, label)
//   Both         CeilingVision::process: one top view, both pipelines (what the observer runs)
//   RenderFrame  for scale: core/camera's renderer on the same views, 1 and 2 x 2 rays per pixel

#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/camera/ceiling_renderer.hpp"
#include "core/vision/ceiling_vision.hpp"
#include "core/vision/image_convert.hpp"

namespace {

using namespace irgs;
using namespace irgs::vision;

struct Frame {
  CeilingView view;
  TopViewGeometry geometry;
  RgbImage image;
};

CeilingScene corridor() {
  CeilingScene scene;
  scene.ceiling_height_m = 2.6;
  for (int i = 0; i < 12; ++i) {
    scene.lights.push_back({Vec2(1.0 + 1.8 * i, 0.0), 0.0, 1.2, 0.1});
    if (i % 3 == 0)
      scene.markers.push_back({Vec2(1.9 + 1.8 * i, 0.6), 0.2, 0.2, 0.2});
  }
  return scene;
}

const std::vector<Frame>& frames() {
  static const std::vector<Frame> all = [] {
    std::vector<Frame> out;
    const CeilingScene scene = corridor();
    const VisionConfig config;
    for (int i = 0; i < 16; ++i) {
      const double tilt = degToRad(35.0 + 55.0 * i / 15.0);
      const CeilingView view(CameraIntrinsics{}, CameraMount{0.1, 0.0, 0.5}, 2.6, tilt);
      RenderSettings s;
      s.seed = static_cast<std::uint64_t>(i + 1);
      const Pose2 pose{0.3 * i, 0.05 * (i % 5) - 0.1, 0.02 * (i % 7) - 0.06};
      out.push_back(
          {view, TopViewGeometry(view, config.top_view), renderCeiling(view, scene, pose, s)});
    }
    return out;
  }();
  return all;
}

void BM_Floor_WarpPerspective_CvtColor(benchmark::State& state) {
  const auto& fs = frames();
  std::size_t i = 0;
  for (auto _ : state) {
    const Frame& f = fs[i++ % fs.size()];
    cv::Mat top = f.geometry.warp(asRgbMat(f.image));
    cv::Mat ycrcb;
    cv::cvtColor(top, ycrcb, cv::COLOR_RGB2YCrCb);
    benchmark::DoNotOptimize(ycrcb.data);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_MarkerPipeline(benchmark::State& state) {
  const auto& fs = frames();
  const VisionConfig config;
  const MarkerDetector detector(config.marker, config.top_view.px_per_m);
  std::size_t i = 0, found = 0;
  for (auto _ : state) {
    const Frame& f = fs[i++ % fs.size()];
    const cv::Mat top = f.geometry.warp(asRgbMat(f.image));
    found += detector.detect(top, f.geometry).markers.size();
  }
  benchmark::DoNotOptimize(found);
  state.SetItemsProcessed(state.iterations());
}

void BM_LightPipeline(benchmark::State& state) {
  const auto& fs = frames();
  const VisionConfig config;
  const LightDetector detector(config.light, config.top_view.px_per_m);
  std::size_t i = 0, found = 0;
  for (auto _ : state) {
    const Frame& f = fs[i++ % fs.size()];
    const cv::Mat top = f.geometry.warp(asRgbMat(f.image));
    found += detector.detect(top, f.geometry).size();
  }
  benchmark::DoNotOptimize(found);
  state.SetItemsProcessed(state.iterations());
}

void BM_BothPipelines(benchmark::State& state) {
  const auto& fs = frames();
  const CeilingVision vision;
  std::size_t i = 0, found = 0;
  for (auto _ : state) {
    const Frame& f = fs[i++ % fs.size()];
    const CeilingVisionResult r = vision.process(f.image, f.view);
    found += r.markers.markers.size() + r.lights.size();
  }
  benchmark::DoNotOptimize(found);
  state.SetItemsProcessed(state.iterations());
}

// For scale: rendering one frame of the same corridor (core/camera), at 1 and 2 x 2 rays per
// pixel (the GUI and VisionCeilingObserver's defaults).
void BM_RenderFrame(benchmark::State& state) {
  const CeilingScene scene = corridor();
  const auto& fs = frames();
  RenderSettings s;
  s.supersample = static_cast<int>(state.range(0));
  std::size_t i = 0;
  for (auto _ : state) {
    const Frame& f = fs[i++ % fs.size()];
    const RgbImage img =
        renderCeiling(f.view, scene, Pose2{0.3 * static_cast<double>(i), 0.0, 0.0}, s);
    benchmark::DoNotOptimize(img.data.data());
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_Floor_WarpPerspective_CvtColor)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MarkerPipeline)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LightPipeline)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BothPipelines)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderFrame)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  frames();  // render outside the timed region
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
