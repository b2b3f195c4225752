#pragma once
// Ceiling-light detection on the top view (002_… 3.5, Figs. 9-10): darken the whole image so
// only lamps stay bright, binarise, erode (drops reflections and afterimages, may split a lamp),
// dilate (joins each lamp into one region), label the regions, and take their centres and long
// axes in the body frame. The lights come out farthest ahead first: lights[0] is the target of
// 002_…'s light-following state.

#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "core/navigation/ceiling_observation.hpp"
#include "core/vision/top_view.hpp"
#include "core/vision/vision_config.hpp"

namespace irgs::vision {

struct LabelledLight {
  LightDetection light;
  std::array<Vec2, 4> box_top_px{};  // the region's minimum-area rectangle, top-view pixels
};

class LightDetector {
 public:
  LightDetector(const LightConfig& config, double px_per_m);

  // `top_view_rgb`: CV_8UC3, R, G, B order. Farthest ahead (largest body x) first.
  std::vector<LabelledLight> detect(const cv::Mat& top_view_rgb,
                                    const TopViewGeometry& geometry) const;
  // The binary image after darkening, threshold, erosion and dilation.
  cv::Mat lightMask(const cv::Mat& top_view_rgb) const;

 private:
  LightConfig config_;
  double px_per_m_;
};

}  // namespace irgs::vision
