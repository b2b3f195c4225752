#include "core/vision/light_detector.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace irgs::vision {

LightDetector::LightDetector(const LightConfig& config, double px_per_m)
    : config_(config), px_per_m_(px_per_m) {}

cv::Mat LightDetector::lightMask(const cv::Mat& top_view_rgb) const {
  cv::Mat grey, dark, binary;
  cv::cvtColor(top_view_rgb, grey, cv::COLOR_RGB2GRAY);
  // (2) lower the brightness: saturating subtraction, only lamps stay bright.
  cv::subtract(grey, cv::Scalar::all(config_.darken), dark);
  // (3) binarise.
  cv::threshold(dark, binary, config_.threshold, 255, cv::THRESH_BINARY);
  // (4) erode, (5) dilate.
  if (config_.erode_px > 1)
    cv::erode(
        binary, binary,
        cv::getStructuringElement(cv::MORPH_RECT, cv::Size(config_.erode_px, config_.erode_px)));
  if (config_.dilate_px > 1)
    cv::dilate(
        binary, binary,
        cv::getStructuringElement(cv::MORPH_RECT, cv::Size(config_.dilate_px, config_.dilate_px)));
  return binary;
}

std::vector<LabelledLight> LightDetector::detect(const cv::Mat& top_view_rgb,
                                                 const TopViewGeometry& geometry) const {
  std::vector<LabelledLight> out;
  if (top_view_rgb.empty())
    return out;
  const cv::Mat binary = lightMask(top_view_rgb);
  // (6) label the regions.
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S);
  const double min_area_px = config_.min_area_m2 * px_per_m_ * px_per_m_;
  // Dilating by more than eroding grows every region by this much on each side.
  const double growth_px = std::max(0, config_.dilate_px - config_.erode_px) / 2.0;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < min_area_px)
      continue;
    const cv::Rect roi(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                       stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    const cv::Mat region = labels(roi) == i;
    std::vector<cv::Point> points;
    cv::findNonZero(region, points);
    for (auto& p : points)
      p += roi.tl();
    const cv::RotatedRect box = cv::minAreaRect(points);
    LabelledLight l;
    cv::Point2f pts[4];
    box.points(pts);
    for (int k = 0; k < 4; ++k)
      l.box_top_px[static_cast<std::size_t>(k)] = Vec2(pts[k].x, pts[k].y);
    const Vec2 centre_px(centroids.at<double>(i, 0), centroids.at<double>(i, 1));
    l.light.centre_body_m = geometry.pixelToBody(centre_px);
    // Long axis in top-view pixels, then in the body frame (x = -row, y = -column).
    const bool wide = box.size.width >= box.size.height;
    const double a = (box.angle + (wide ? 0.0 : 90.0)) * kPi / 180.0;
    const double axis_body = std::atan2(-std::cos(a), -std::sin(a));
    l.light.axis_rad = std::remainder(axis_body, kPi);
    const double long_px = std::max(box.size.width, box.size.height) - 2.0 * growth_px;
    l.light.length_m = std::max(long_px, 1.0) / px_per_m_;
    out.push_back(l);
  }
  // (7) farthest ahead first.
  std::sort(out.begin(), out.end(), [](const LabelledLight& a, const LabelledLight& b) {
    return a.light.centre_body_m.x() > b.light.centre_body_m.x();
  });
  return out;
}

}  // namespace irgs::vision
