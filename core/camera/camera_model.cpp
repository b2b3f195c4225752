#include "core/camera/camera_model.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace irgs {

Eigen::Matrix3d CameraIntrinsics::matrix() const {
  Eigen::Matrix3d k;
  k << fx_px, skew, cx_px, 0.0, fy_px, cy_px, 0.0, 0.0, 1.0;
  return k;
}

Eigen::Matrix3d cameraToBodyRotation(double tilt_rad) {
  const double c = std::cos(tilt_rad), s = std::sin(tilt_rad);
  // z_c: the optical axis, forward and up; x_c: the robot's right; y_c = z_c x x_c.
  const Eigen::Vector3d z_c(c, 0.0, s);
  const Eigen::Vector3d x_c(0.0, -1.0, 0.0);
  const Eigen::Vector3d y_c = z_c.cross(x_c);
  Eigen::Matrix3d r;
  r.col(0) = x_c;
  r.col(1) = y_c;
  r.col(2) = z_c;
  return r;
}

CeilingView::CeilingView(const CameraIntrinsics& intrinsics, const CameraMount& mount,
                         double ceiling_height_m, double tilt_rad)
    : intrinsics_(intrinsics),
      mount_(mount),
      ceiling_height_m_(ceiling_height_m),
      tilt_rad_(tilt_rad),
      rotation_(cameraToBodyRotation(tilt_rad)) {
  if (!(intrinsics.fx_px > 0.0) || !(intrinsics.fy_px > 0.0) || intrinsics.width_px <= 0 ||
      intrinsics.height_px <= 0)
    throw std::invalid_argument("CeilingView: intrinsics must be positive");
  if (!(ceiling_height_m - mount.z_m > 0.0))
    throw std::invalid_argument("CeilingView: the ceiling must be above the camera");
  const Eigen::Matrix3d k = intrinsics.matrix();
  k_inv_ = k.inverse();
  // (7) M = K R^T [e1 e2 t], t = (-mx, -my, h): the plane homography of A002-1.
  Eigen::Matrix3d plane;
  plane << 1.0, 0.0, -mount.x_m, 0.0, 1.0, -mount.y_m, 0.0, 0.0, heightAboveCameraM();
  ceiling_to_image_ = k * rotation_.transpose() * plane;
}

std::optional<Vec2> CeilingView::project(const Vec2& ceiling_point_body) const {
  const Eigen::Vector3d q =
      ceiling_to_image_ * Eigen::Vector3d(ceiling_point_body.x(), ceiling_point_body.y(), 1.0);
  if (!(q.z() > 1e-12))  // behind the camera
    return std::nullopt;
  return Vec2(q.x() / q.z(), q.y() / q.z());
}

Eigen::Vector3d CeilingView::rayBody(const Vec2& pixel) const {
  return rotation_ * (k_inv_ * Eigen::Vector3d(pixel.x(), pixel.y(), 1.0));
}

std::optional<Vec2> CeilingView::backProject(const Vec2& pixel) const {
  const Eigen::Vector3d d = rayBody(pixel);
  if (!(d.z() > 1e-9))
    return std::nullopt;
  const double t = heightAboveCameraM() / d.z();
  return Vec2(mount_.x_m + t * d.x(), mount_.y_m + t * d.y());
}

bool CeilingView::inImage(const Vec2& pixel, double margin_px) const {
  return pixel.x() >= -0.5 + margin_px && pixel.y() >= -0.5 + margin_px &&
         pixel.x() <= intrinsics_.width_px - 0.5 - margin_px &&
         pixel.y() <= intrinsics_.height_px - 0.5 - margin_px;
}

}  // namespace irgs
