#include "core/camera/ceiling_camera_config.hpp"

#include <cmath>
#include <set>

namespace irgs {
namespace {

using Json = nlohmann::json;

class Reader {
 public:
  explicit Reader(std::vector<std::string>& errors) : errors_(errors) {}

  // Reads object[key] into `out` (times `scale`) when present; requires a number > 0 when
  // `positive`, otherwise any finite number.
  void number(const Json& object, const std::string& ptr, const char* key, double& out,
              bool positive, double scale = 1.0) {
    const auto it = object.find(key);
    if (it == object.end())
      return;
    const std::string field = ptr + "/" + key;
    if (!it->is_number()) {
      errors_.push_back(field + ": expected a number");
      return;
    }
    const double v = it->get<double>();
    if (!std::isfinite(v) || (positive && !(v > 0.0))) {
      errors_.push_back(field + (positive ? ": expected a number > 0" : ": expected a number"));
      return;
    }
    out = v * scale;
  }
  void integer(const Json& object, const std::string& ptr, const char* key, int& out) {
    const auto it = object.find(key);
    if (it == object.end())
      return;
    if (!it->is_number_integer() || it->get<long long>() <= 0 || it->get<long long>() > 16384) {
      errors_.push_back(ptr + "/" + key + ": expected an integer in 1..16384");
      return;
    }
    out = static_cast<int>(it->get<long long>());
  }
  const Json* object(const Json& parent, const std::string& ptr, const char* key) {
    const auto it = parent.find(key);
    if (it == parent.end())
      return nullptr;
    if (!it->is_object()) {
      errors_.push_back(ptr + "/" + key + ": expected an object");
      return nullptr;
    }
    return &*it;
  }
  void unknown(const Json& object, const std::string& ptr, const std::set<std::string>& known) {
    for (auto it = object.begin(); it != object.end(); ++it)
      if (!known.count(it.key()))
        errors_.push_back(ptr + "/" + it.key() + ": unknown key");
  }

 private:
  std::vector<std::string>& errors_;
};

constexpr double kDeg = 3.14159265358979323846 / 180.0;

}  // namespace

CeilingCameraConfigResult ceilingCameraFromJson(const Json& o) {
  CeilingCameraConfigResult result;
  const std::string ptr = "/ceiling_camera";
  if (!o.is_object()) {
    result.errors.push_back(ptr + ": expected an object");
    return result;
  }
  Reader r(result.errors);
  CeilingCameraConfig& c = result.config;
  r.integer(o, ptr, "width_px", c.intrinsics.width_px);
  r.integer(o, ptr, "height_px", c.intrinsics.height_px);
  // A changed image size moves the default principal point and focal length with it.
  c.intrinsics.cx_px = (c.intrinsics.width_px - 1) / 2.0;
  c.intrinsics.cy_px = (c.intrinsics.height_px - 1) / 2.0;
  c.intrinsics.fx_px = c.intrinsics.fy_px = c.intrinsics.width_px / 2.0 / std::tan(30.0 * kDeg);
  r.number(o, ptr, "fx_px", c.intrinsics.fx_px, true);
  c.intrinsics.fy_px = c.intrinsics.fx_px;
  r.number(o, ptr, "fy_px", c.intrinsics.fy_px, true);
  r.number(o, ptr, "cx_px", c.intrinsics.cx_px, false);
  r.number(o, ptr, "cy_px", c.intrinsics.cy_px, false);
  r.number(o, ptr, "skew", c.intrinsics.skew, false);
  if (const Json* m = r.object(o, ptr, "mount")) {
    r.number(*m, ptr + "/mount", "x_m", c.mount.x_m, false);
    r.number(*m, ptr + "/mount", "y_m", c.mount.y_m, false);
    r.number(*m, ptr + "/mount", "z_m", c.mount.z_m, true);
    r.unknown(*m, ptr + "/mount", {"x_m", "y_m", "z_m"});
  }
  if (const Json* t = r.object(o, ptr, "tilt")) {
    const std::string tp = ptr + "/tilt";
    r.number(*t, tp, "min_deg", c.tilt.min_tilt_rad, true, kDeg);
    r.number(*t, tp, "max_deg", c.tilt.max_tilt_rad, true, kDeg);
    r.number(*t, tp, "near_m", c.tilt.near_m, false);
    r.number(*t, tp, "far_m", c.tilt.far_m, true);
    r.number(*t, tp, "rate_degps", c.tilt_rate_radps, true, kDeg);
    r.unknown(*t, tp, {"min_deg", "max_deg", "near_m", "far_m", "rate_degps"});
    if (!(c.tilt.near_m < c.tilt.far_m))
      result.errors.push_back(tp + ": near_m must be below far_m");
    if (!(c.tilt.min_tilt_rad <= c.tilt.max_tilt_rad) || c.tilt.max_tilt_rad > 90.0 * kDeg + 1e-9)
      result.errors.push_back(tp + ": expected 0 < min_deg <= max_deg <= 90");
  }
  r.number(o, ptr, "working_range_m", c.working_range_m, true);
  if (o.contains("ceiling_height_m")) {
    double h = 0.0;
    r.number(o, ptr, "ceiling_height_m", h, true);
    if (h > 0.0)
      c.ceiling_height_m = h;
  }
  r.unknown(o, ptr,
            {"width_px", "height_px", "fx_px", "fy_px", "cx_px", "cy_px", "skew", "mount", "tilt",
             "working_range_m", "ceiling_height_m"});
  if (!result.errors.empty())
    result.config = CeilingCameraConfig{};
  return result;
}

CeilingCameraConfigResult ceilingCameraFromProfile(const RobotProfile& profile) {
  const auto it = profile.extra.find("ceiling_camera");
  if (it == profile.extra.end())
    return {};
  return ceilingCameraFromJson(*it);
}

Json ceilingCameraToJson(const CeilingCameraConfig& c) {
  Json o;
  o["width_px"] = c.intrinsics.width_px;
  o["height_px"] = c.intrinsics.height_px;
  o["fx_px"] = c.intrinsics.fx_px;
  o["fy_px"] = c.intrinsics.fy_px;
  o["cx_px"] = c.intrinsics.cx_px;
  o["cy_px"] = c.intrinsics.cy_px;
  o["skew"] = c.intrinsics.skew;
  o["mount"] = {{"x_m", c.mount.x_m}, {"y_m", c.mount.y_m}, {"z_m", c.mount.z_m}};
  o["tilt"] = {{"min_deg", c.tilt.min_tilt_rad / kDeg},
               {"max_deg", c.tilt.max_tilt_rad / kDeg},
               {"near_m", c.tilt.near_m},
               {"far_m", c.tilt.far_m},
               {"rate_degps", c.tilt_rate_radps / kDeg}};
  o["working_range_m"] = c.working_range_m;
  if (c.ceiling_height_m)
    o["ceiling_height_m"] = *c.ceiling_height_m;
  return o;
}

}  // namespace irgs
