#include "core/vision/marker_detector.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace irgs::vision {
namespace {

cv::Mat squareKernel(int px) {
  return cv::getStructuringElement(cv::MORPH_RECT, cv::Size(px, px));
}

// Orders four points counter-clockwise in the image (clockwise on screen) from the first.
std::array<cv::Point2f, 4> orderedCorners(const std::vector<cv::Point2f>& pts) {
  cv::Point2f c(0.f, 0.f);
  for (const auto& p : pts)
    c += p;
  c *= 0.25f;
  std::array<cv::Point2f, 4> out{pts[0], pts[1], pts[2], pts[3]};
  std::sort(out.begin(), out.end(), [&](const cv::Point2f& a, const cv::Point2f& b) {
    return std::atan2(a.y - c.y, a.x - c.x) < std::atan2(b.y - c.y, b.x - c.x);
  });
  return out;
}

}  // namespace

MarkerDetector::MarkerDetector(const MarkerConfig& config, double px_per_m)
    : config_(config), px_per_m_(px_per_m) {
  const int n = config.template_px + 2 * config.template_margin_px;
  template_ = cv::Mat::zeros(n, n, CV_32F);
  template_(cv::Rect(config.template_margin_px, config.template_margin_px, config.template_px,
                     config.template_px))
      .setTo(1.0f);
}

void MarkerDetector::crAndMask(const cv::Mat& top_view_rgb, cv::Mat& cr, cv::Mat& mask) const {
  // (2) YCbCr, (3) Cr threshold, (4) opening (speckles) and closing (holes).
  cv::Mat ycrcb;
  cv::cvtColor(top_view_rgb, ycrcb, cv::COLOR_RGB2YCrCb);
  cv::extractChannel(ycrcb, cr, 1);
  cv::threshold(cr, mask, config_.cr_threshold, 255, cv::THRESH_BINARY);
  if (config_.open_px > 1)
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN, squareKernel(config_.open_px));
  if (config_.close_px > 1)
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, squareKernel(config_.close_px));
}

cv::Mat MarkerDetector::redMask(const cv::Mat& top_view_rgb) const {
  cv::Mat cr, mask;
  crAndMask(top_view_rgb, cr, mask);
  return mask;
}

MarkerDetectionResult MarkerDetector::detect(const cv::Mat& top_view_rgb,
                                             const TopViewGeometry& geometry) const {
  MarkerDetectionResult result;
  if (top_view_rgb.empty())
    return result;
  cv::Mat cr, mask;
  crAndMask(top_view_rgb, cr, mask);

  // (5) contours and their vertices.
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  const double side_px = config_.size_m * px_per_m_;
  const double min_area_px = 0.25 * std::pow(side_px * (1.0 - config_.size_tolerance), 2);
  const int tn = template_.rows;
  const float inner0 = static_cast<float>(config_.template_margin_px);
  const float inner1 = static_cast<float>(config_.template_margin_px + config_.template_px);
  const std::array<cv::Point2f, 4> target{cv::Point2f(inner0, inner0), cv::Point2f(inner1, inner0),
                                          cv::Point2f(inner1, inner1), cv::Point2f(inner0, inner1)};
  cv::Mat cr_float;
  cr.convertTo(cr_float, CV_32F);
  for (const auto& contour : contours) {
    MarkerCandidate cand;
    const double area = cv::contourArea(contour);
    const cv::RotatedRect box = cv::minAreaRect(contour);
    {
      cv::Point2f pts[4];
      box.points(pts);
      for (int i = 0; i < 4; ++i)
        cand.corners_top_px[static_cast<std::size_t>(i)] = Vec2(pts[i].x, pts[i].y);
    }
    cand.centre_body_m = geometry.pixelToBody(Vec2(box.center.x, box.center.y));
    if (area < min_area_px) {
      result.candidates.push_back(cand);
      continue;
    }
    std::vector<cv::Point> approx;
    cv::approxPolyDP(contour, approx, config_.approx_epsilon * cv::arcLength(contour, true), true);
    std::vector<cv::Point2f> quad;
    if (approx.size() == 4 && cv::isContourConvex(approx)) {
      for (const auto& p : approx)
        quad.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
    } else {
      cv::Point2f pts[4];
      box.points(pts);
      quad.assign(pts, pts + 4);
    }
    const std::array<cv::Point2f, 4> q = orderedCorners(quad);
    for (std::size_t i = 0; i < 4; ++i)
      cand.corners_top_px[i] = Vec2(q[i].x, q[i].y);
    const double quad_area =
        std::abs(cv::contourArea(std::vector<cv::Point2f>(q.begin(), q.end())));
    if (quad_area <= 0.0 || area / quad_area < config_.min_fill) {
      cand.verdict = CandidateVerdict::kNotFourSided;
      result.candidates.push_back(cand);
      continue;
    }
    // The top view is metric: every side must be the marker's side.
    double side_sum = 0.0;
    bool sides_ok = true;
    for (std::size_t i = 0; i < 4; ++i) {
      const cv::Point2f d = q[(i + 1) % 4] - q[i];
      const double side = std::hypot(d.x, d.y) + 1.0;  // +1: pixel extent, not centre distance
      side_sum += side;
      if (std::abs(side / side_px - 1.0) > config_.size_tolerance)
        sides_ok = false;
    }
    cand.mean_side_m = side_sum / 4.0 / px_per_m_;
    cv::Point2f centre(0.f, 0.f);
    for (const auto& p : q)
      centre += p;
    centre *= 0.25f;
    cand.centre_body_m = geometry.pixelToBody(Vec2(centre.x, centre.y));
    if (!sides_ok) {
      cand.verdict = CandidateVerdict::kWrongSize;
      result.candidates.push_back(cand);
      continue;
    }
    // (6) template matching on the rectified candidate (Cr channel, normalised correlation).
    const cv::Mat h = cv::getPerspectiveTransform(q.data(), target.data());
    cv::Mat patch;
    cv::warpPerspective(cr_float, patch, h, cv::Size(tn, tn), cv::INTER_LINEAR,
                        cv::BORDER_REPLICATE);
    cv::Mat score;
    cv::matchTemplate(patch, template_, score, cv::TM_CCOEFF_NORMED);
    cand.score = std::clamp(static_cast<double>(score.at<float>(0, 0)), 0.0, 1.0);
    if (cand.score < config_.min_score) {
      cand.verdict = CandidateVerdict::kPoorMatch;
      result.candidates.push_back(cand);
      continue;
    }
    cand.verdict = CandidateVerdict::kAccepted;
    // (7) the centre in metres, and the orientation (mod 90 deg) from the first side.
    MarkerDetection det;
    det.centre_body_m = cand.centre_body_m;
    const Vec2 a = geometry.pixelToBody(Vec2(q[0].x, q[0].y));
    const Vec2 b = geometry.pixelToBody(Vec2(q[1].x, q[1].y));
    const double angle = std::atan2(b.y() - a.y(), b.x() - a.x());
    det.heading_rad = std::remainder(angle, 0.5 * kPi);
    det.score = cand.score;
    result.markers.push_back(det);
    result.candidates.push_back(cand);
  }
  std::sort(result.markers.begin(), result.markers.end(),
            [](const MarkerDetection& x, const MarkerDetection& y) {
              return x.centre_body_m.norm() < y.centre_body_m.norm();
            });
  return result;
}

}  // namespace irgs::vision
