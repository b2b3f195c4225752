#include "core/estimation/mouse_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs {

namespace {

double sinc(double x) {
  return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}

Vec2 rotate(const Vec2& v, double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// (7)-(10) for one sensor: its position after the interval in the start body frame. The paper's
// r * (sin(a + dθ) - sin a) * sign(dθ) with r = l / |dθ| equals l * sinc(dθ/2) * cos(a + dθ/2)
// (and likewise for y), which has the straight-line limit built in (A004-6).
Vec2 sensorEnd(const Vec2& start, const SensorMotion& m, double dtheta) {
  const double half = 0.5 * dtheta;
  const double chord = m.length_m * sinc(half);
  return start + chord * Vec2(std::cos(m.alpha_rad + half), std::sin(m.alpha_rad + half));
}

void addError(std::vector<Diagnostic>& out, const std::string& field, const std::string& message) {
  out.push_back({Severity::kError, "", 0, 0, field, message});
}

// A finite number at object[key]; missing is an error only when required.
std::optional<double> readNumber(const nlohmann::json& object, const std::string& pointer,
                                 const char* key, bool required, std::vector<Diagnostic>& out) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (required)
      addError(out, pointer + "/" + key, "required number is missing");
    return std::nullopt;
  }
  if (!it->is_number() || !std::isfinite(it->get<double>())) {
    addError(out, pointer + "/" + key, "expected a finite number");
    return std::nullopt;
  }
  return it->get<double>();
}

void readMount(const nlohmann::json& sensors, const std::string& pointer, const char* key,
               MouseMount& mount, std::vector<Diagnostic>& out) {
  const auto it = sensors.find(key);
  const std::string ptr = pointer + "/" + key;
  if (it == sensors.end() || !it->is_object()) {
    addError(out, ptr, "required object {x_m, y_m, heading_deg} is missing");
    return;
  }
  if (const auto v = readNumber(*it, ptr, "x_m", true, out))
    mount.x_m = *v;
  if (const auto v = readNumber(*it, ptr, "y_m", true, out))
    mount.y_m = *v;
  if (const auto v = readNumber(*it, ptr, "heading_deg", true, out))
    mount.phi_rad = degToRad(*v);
}

}  // namespace

MouseRigResult mouseRigFromProfile(const RobotProfile& profile) {
  MouseRigResult result;
  const std::string pointer = "/drive/mouse_sensors";
  const auto it = profile.drive.extra.find("mouse_sensors");
  if (it == profile.drive.extra.end() || !it->is_object()) {
    addError(result.diagnostics, pointer, "required object is missing (drive type mouse_sensor)");
    return result;
  }
  MouseRig rig;
  const struct {
    const char* key;
    double* value;
  } spec_fields[] = {{"counts_per_inch", &rig.spec.counts_per_inch},
                     {"max_speed_mps", &rig.spec.max_speed_mps},
                     {"max_lift_m", &rig.spec.max_lift_m},
                     {"frame_rate_hz", &rig.spec.frame_rate_hz}};
  for (const auto& f : spec_fields) {
    if (const auto v = readNumber(*it, pointer, f.key, false, result.diagnostics)) {
      if (*v > 0.0)
        *f.value = *v;
      else
        addError(result.diagnostics, pointer + "/" + f.key, "must be > 0");
    }
  }
  readMount(*it, pointer, "right", rig.right, result.diagnostics);
  readMount(*it, pointer, "left", rig.left, result.diagnostics);
  if (hasErrors(result.diagnostics))
    return result;
  if (!(rig.separation_m() >= 1e-3)) {
    addError(result.diagnostics, pointer, "the two sensors must be at least 1 mm apart");
    return result;
  }
  result.rig = rig;
  return result;
}

MouseRig symmetricMouseRig(double separation_m, MouseSensorSpec spec) {
  MouseRig rig;
  rig.spec = spec;
  rig.right = {0.0, -0.5 * separation_m, 0.0};
  rig.left = {0.0, 0.5 * separation_m, 0.0};
  validate(rig);
  return rig;
}

void validate(const MouseRig& rig) {
  validate(rig.spec);
  for (const MouseMount* m : {&rig.right, &rig.left}) {
    if (!std::isfinite(m->x_m) || !std::isfinite(m->y_m) || !std::isfinite(m->phi_rad))
      throw std::invalid_argument("MouseRig: non-finite sensor mount");
  }
  if (!(rig.separation_m() >= 1e-3))
    throw std::invalid_argument("MouseRig: the two sensors must be at least 1 mm apart");
}

const char* toString(MouseMotionStatus status) {
  switch (status) {
    case MouseMotionStatus::kOk:
      return "ok";
    case MouseMotionStatus::kSaturated:
      return "saturated";
    case MouseMotionStatus::kLostTracking:
      return "lost tracking";
  }
  return "unknown";
}

TwoSensorMotion inferTwoSensorMotion(const MouseRig& rig, const Vec2& right_m, const Vec2& left_m) {
  TwoSensorMotion out;
  if (!right_m.allFinite() || !left_m.allFinite()) {
    out.status = MouseMotionStatus::kLostTracking;
    return out;
  }
  // Sensor axes -> body axes.
  const Vec2 cr = rotate(right_m, rig.right.phi_rad);
  const Vec2 cl = rotate(left_m, rig.left.phi_rad);
  // (1)-(3) per sensor.
  out.right = sensorMotion(cr.x(), cr.y());
  out.left = sensorMotion(cl.x(), cl.y());
  // gamma = alpha_r - alpha_l (A004-2).
  out.gamma_rad = out.right.alpha_rad - out.left.alpha_rad;

  const Vec2 pr = rig.right.position(), pl = rig.left.position();
  const Vec2 baseline = pl - pr;
  const double d = baseline.norm();
  // A rigid rotation moves the left sensor relative to the right one by dθ perp(baseline)
  // (perp = +90 deg). Its sign is (6)'s sign(y_r - y_l) in the paper's frame (forward
  // difference of the readings, right minus left, for the paper's rig).
  const Vec2 perp(-baseline.y(), baseline.x());
  const Vec2 relative = cl - cr;
  const double along = relative.dot(perp);
  // (6) |dθ| = sqrt(l_l^2 + l_r^2 - 2 cos(gamma) l_l l_r) / D. The root is the law of cosines
  // for |c_l - c_r|, computed directly here: the printed form cancels catastrophically for
  // nearly straight motion (l_l ~ l_r, gamma ~ 0) and loses the rotation below ~1e-8 rad.
  const double magnitude = relative.norm() / d;
  out.dtheta_rad = along > 0.0 ? magnitude : along < 0.0 ? -magnitude : 0.0;
  out.rigidity_residual_m = std::abs(relative.dot(baseline)) / d;

  // (4)/(5) radii r = l / |dθ| and (7)-(10) sensor end positions, in the singularity-free form.
  out.right_end = sensorEnd(pr, out.right, out.dtheta_rad);
  out.left_end = sensorEnd(pl, out.left, out.dtheta_rad);
  // (11)/(12): midpoint of the sensors after the interval; for a rig not centred on the body
  // origin, subtract where the rotated midpoint offset went.
  const Vec2 mid0 = 0.5 * (pr + pl);
  out.centre = 0.5 * (out.right_end + out.left_end) - rotate(mid0, out.dtheta_rad);
  return out;
}

TwoSensorMotion inferTwoSensorMotion(const MouseRig& rig, const MouseCounts& right,
                                     const MouseCounts& left) {
  if (right.status == MouseStatus::kLifted || left.status == MouseStatus::kLifted) {
    TwoSensorMotion out;
    out.status = MouseMotionStatus::kLostTracking;
    return out;
  }
  const double k = rig.spec.metresPerCount();
  TwoSensorMotion out = inferTwoSensorMotion(
      rig, Vec2(k * static_cast<double>(right.dx), k * static_cast<double>(right.dy)),
      Vec2(k * static_cast<double>(left.dx), k * static_cast<double>(left.dy)));
  if (right.status == MouseStatus::kSaturated || left.status == MouseStatus::kSaturated)
    out.status = MouseMotionStatus::kSaturated;
  return out;
}

MouseOdometry::MouseOdometry(MouseRig rig, const Pose2& start) : rig_(rig) {
  validate(rig_);
  reset(start);
}

void MouseOdometry::reset(const Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta))
    throw std::invalid_argument("MouseOdometry: non-finite pose");
  pose_ = {pose.x, pose.y, wrapAngle(pose.theta)};
  distance_m_ = 0.0;
  lost_intervals_ = 0;
  saturated_intervals_ = 0;
}

TwoSensorMotion MouseOdometry::update(const MouseCounts& right, const MouseCounts& left) {
  const TwoSensorMotion m = inferTwoSensorMotion(rig_, right, left);
  if (m.status == MouseMotionStatus::kLostTracking) {
    ++lost_intervals_;
    return m;
  }
  if (m.status == MouseMotionStatus::kSaturated)
    ++saturated_intervals_;
  // (13)/(14) as a plain rotation of (Δx, Δy) by theta_t (A004-5: no arctan quadrant problem);
  // (15) theta_{t+1} = theta_t + Δθ.
  pose_.x += m.centre.x() * std::cos(pose_.theta) - m.centre.y() * std::sin(pose_.theta);
  pose_.y += m.centre.x() * std::sin(pose_.theta) + m.centre.y() * std::cos(pose_.theta);
  pose_.theta = wrapAngle(pose_.theta + m.dtheta_rad);
  distance_m_ += m.centre.norm();
  return m;
}

}  // namespace irgs
