#pragma once
// The top-view (inverse perspective) transform of 002_… 3.4 as a plane homography (A002-1):
// the ceiling region the camera sees, clipped to a working rectangle in the body frame, is
// warped into an image where 1 pixel is 1 / px_per_m metres. Row 0 is the far edge (forward is
// up), column 0 the left edge.
//
// Top-view pixel (c, r) <-> body ceiling point (X, Y):  X = x_far - r / s,  Y = y_left - c / s.
// The frame pixel of a top-view pixel is  M * S * (c, r, 1)^T  with M the ceiling-to-image
// homography of the camera (core/camera) and S the metric map above (A002-2: the ROI points go
// through the full M).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>

#include "core/camera/camera_model.hpp"
#include "core/geometry/types.hpp"
#include "core/vision/vision_config.hpp"

namespace irgs::vision {

class TopViewGeometry {
 public:
  // The working rectangle: the part of the ceiling the camera sees (image border rays), clipped
  // to max_range_m ahead and max_half_width_m to each side. Empty (width 0) when the camera
  // sees no ceiling.
  TopViewGeometry(const CeilingView& view, const TopViewConfig& config);

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ <= 0 || height_ <= 0; }
  double pxPerM() const { return px_per_m_; }
  double xNearM() const { return x_near_m_; }
  double xFarM() const { return x_far_m_; }
  double yLeftM() const { return y_left_m_; }
  double yRightM() const { return y_right_m_; }

  Vec2 pixelToBody(const Vec2& px) const {
    return {x_far_m_ - px.y() / px_per_m_, y_left_m_ - px.x() / px_per_m_};
  }
  Vec2 bodyToPixel(const Vec2& body) const {
    return {(y_left_m_ - body.y()) * px_per_m_, (x_far_m_ - body.x()) * px_per_m_};
  }
  // Frame pixel <- top-view pixel (for cv::warpPerspective with WARP_INVERSE_MAP).
  const Eigen::Matrix3d& frameFromTopView() const { return frame_from_top_; }
  cv::Mat frameFromTopViewMat() const;

  // Warps `frame` (any type OpenCV warps) into the top view; pixels outside the frame are 0.
  cv::Mat warp(const cv::Mat& frame, int interpolation = 1 /* cv::INTER_LINEAR */) const;

 private:
  double px_per_m_;
  double x_near_m_ = 0.0, x_far_m_ = 0.0, y_left_m_ = 0.0, y_right_m_ = 0.0;
  int width_ = 0, height_ = 0;
  Eigen::Matrix3d frame_from_top_ = Eigen::Matrix3d::Identity();
};

}  // namespace irgs::vision
