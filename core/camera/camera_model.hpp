#pragma once
// The ceiling camera of 002_…: a pinhole camera on a tilt servo, mounted on the robot and looking
// forward and up at the ceiling plane. Lens distortion is not modelled (rendered frames have
// none; real frames are expected to be undistorted before the pipelines, docs/decisions.md).
//
// Frames. Body: x forward, y left, z up, origin on the floor midway between the wheels. Camera
// (OpenCV convention): z along the optical axis, x to the image's right (the robot's right), y
// down the image. The tilt theta is the angle between the optical axis and the ceiling plane
// (002_… 3.4): 90 deg looks straight up, 35 deg looks far ahead; the axis stays in the body
// x-z plane. Looking up, the far ceiling appears at the bottom of the image.
//
// The ceiling-to-image map is the plane homography of A002-1: for a ceiling point (X, Y) in
// the body frame, (u, v, 1)^T ~ M (X, Y, 1)^T with M = K R^T [e1 e2 (-mx, -my, h)^T], h the
// height of the ceiling above the camera.

#include <Eigen/Core>
#include <optional>

#include "core/geometry/types.hpp"

namespace irgs {

// Pinhole intrinsics in pixels. 640 x 480 with a 60 deg horizontal field of view by default
// (the SPC-A130MB webcam of 002_… is 640 x 480; its focal length is not printed).
struct CameraIntrinsics {
  int width_px = 640;
  int height_px = 480;
  double fx_px = 554.256;  // 320 / tan(30 deg)
  double fy_px = 554.256;
  double cx_px = 319.5;
  double cy_px = 239.5;
  double skew = 0.0;

  Eigen::Matrix3d matrix() const;
};

// Where the tilt axis sits on the robot (body frame, z above the floor).
struct CameraMount {
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.5;
};

// Camera-to-body rotation for tilt `tilt_rad` (columns: the camera axes in the body frame).
Eigen::Matrix3d cameraToBodyRotation(double tilt_rad);

// The camera pose for one frame: intrinsics, mount and tilt, and the ceiling height above the
// floor. All maps between the image and the ceiling plane go through here.
class CeilingView {
 public:
  // Throws std::invalid_argument unless the ceiling is above the camera and the intrinsics
  // are positive.
  CeilingView(const CameraIntrinsics& intrinsics, const CameraMount& mount, double ceiling_height_m,
              double tilt_rad);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  const CameraMount& mount() const { return mount_; }
  double tiltRad() const { return tilt_rad_; }
  double ceilingHeightM() const { return ceiling_height_m_; }
  // Height of the ceiling above the camera's centre (h of 002_…).
  double heightAboveCameraM() const { return ceiling_height_m_ - mount_.z_m; }

  // M: ceiling (X, Y) body frame metres -> image pixels (homogeneous).
  const Eigen::Matrix3d& ceilingToImage() const { return ceiling_to_image_; }

  // The pixel where the ceiling point (body frame) appears, nothing when it is behind the
  // camera. The pixel may lie outside the image.
  std::optional<Vec2> project(const Vec2& ceiling_point_body) const;
  // The ceiling point (body frame) seen at `pixel`, nothing when that ray misses the ceiling
  // (points at or below the horizon).
  std::optional<Vec2> backProject(const Vec2& pixel) const;
  // The ray through `pixel` in the body frame (not normalised).
  Eigen::Vector3d rayBody(const Vec2& pixel) const;
  bool inImage(const Vec2& pixel, double margin_px = 0.0) const;

 private:
  CameraIntrinsics intrinsics_;
  CameraMount mount_;
  double ceiling_height_m_;
  double tilt_rad_;
  Eigen::Matrix3d rotation_;  // camera -> body
  Eigen::Matrix3d k_inv_;
  Eigen::Matrix3d ceiling_to_image_;
};

}  // namespace irgs
