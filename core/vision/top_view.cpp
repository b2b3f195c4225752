#include "core/vision/top_view.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace irgs::vision {

TopViewGeometry::TopViewGeometry(const CeilingView& view, const TopViewConfig& config)
    : px_per_m_(config.px_per_m) {
  // The footprint of the image on the ceiling, sampled along the image border (a ray of the
  // border that misses the ceiling, or lands beyond the range, is clipped to the range).
  const int w = view.intrinsics().width_px, h = view.intrinsics().height_px;
  double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
  auto add = [&](double u, double v) {
    const auto p = view.backProject(Vec2(u, v));
    if (!p)
      return;
    const double x = std::min(p->x(), config.max_range_m);
    const double y = std::clamp(p->y(), -config.max_half_width_m, config.max_half_width_m);
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
  };
  constexpr int kSteps = 32;
  for (int i = 0; i <= kSteps; ++i) {
    const double u = -0.5 + w * static_cast<double>(i) / kSteps;
    const double v = -0.5 + h * static_cast<double>(i) / kSteps;
    add(u, -0.5);
    add(u, h - 0.5);
    add(-0.5, v);
    add(w - 0.5, v);
  }
  // When the border rays miss the ceiling (grazing), a border point beyond the range does not
  // show; the farthest ceiling is then the range itself wherever the image still sees it.
  if (x_min > x_max)
    return;
  if (view.backProject(Vec2(0.5 * w, h - 0.5)) == std::nullopt)
    x_max = config.max_range_m;
  x_near_m_ = x_min;
  x_far_m_ = x_max;
  y_left_m_ = y_max;
  y_right_m_ = y_min;
  width_ = static_cast<int>(std::ceil((y_left_m_ - y_right_m_) * px_per_m_));
  height_ = static_cast<int>(std::ceil((x_far_m_ - x_near_m_) * px_per_m_));
  Eigen::Matrix3d s;
  s << 0.0, -1.0 / px_per_m_, x_far_m_, -1.0 / px_per_m_, 0.0, y_left_m_, 0.0, 0.0, 1.0;
  frame_from_top_ = view.ceilingToImage() * s;
}

cv::Mat TopViewGeometry::frameFromTopViewMat() const {
  cv::Mat m(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      m.at<double>(r, c) = frame_from_top_(r, c);
  return m;
}

cv::Mat TopViewGeometry::warp(const cv::Mat& frame, int interpolation) const {
  cv::Mat out;
  if (empty())
    return cv::Mat(0, 0, frame.type());
  cv::warpPerspective(frame, out, frameFromTopViewMat(), cv::Size(width_, height_),
                      interpolation | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                      cv::Scalar::all(0));
  return out;
}

}  // namespace irgs::vision
