#include "core/vision/vision_config.hpp"

#include <cmath>
#include <set>
#include <type_traits>

namespace irgs::vision {
namespace {

using Json = nlohmann::json;

struct Reader {
  std::vector<std::string>& errors;

  const Json* section(const Json& root, const char* key) {
    const auto it = root.find(key);
    if (it == root.end())
      return nullptr;
    if (!it->is_object()) {
      errors.push_back(std::string("/") + key + ": expected an object");
      return nullptr;
    }
    return &*it;
  }
  template <typename T>
  void read(const Json& o, const std::string& ptr, const char* key, T& out, double lo, double hi) {
    const auto it = o.find(key);
    if (it == o.end())
      return;
    const std::string field = ptr + "/" + key;
    if (!it->is_number() || (std::is_integral_v<T> && !it->is_number_integer())) {
      errors.push_back(field +
                       (std::is_integral_v<T> ? ": expected an integer" : ": expected a number"));
      return;
    }
    const double v = it->get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) {
      errors.push_back(field + ": expected a value in " + Json(lo).dump() + ".." + Json(hi).dump());
      return;
    }
    out = static_cast<T>(v);
  }
  void unknown(const Json& o, const std::string& ptr, const std::set<std::string>& known) {
    for (auto it = o.begin(); it != o.end(); ++it)
      if (!known.count(it.key()))
        errors.push_back(ptr + "/" + it.key() + ": unknown key");
  }
};

}  // namespace

VisionConfigResult visionConfigFromJson(const Json& root) {
  VisionConfigResult result;
  if (!root.is_object()) {
    result.errors.push_back(": expected an object");
    return result;
  }
  Reader r{result.errors};
  VisionConfig& c = result.config;
  if (const Json* t = r.section(root, "top_view")) {
    r.read(*t, "/top_view", "px_per_m", c.top_view.px_per_m, 5.0, 1000.0);
    r.read(*t, "/top_view", "max_range_m", c.top_view.max_range_m, 0.1, 100.0);
    r.read(*t, "/top_view", "max_half_width_m", c.top_view.max_half_width_m, 0.1, 100.0);
    r.unknown(*t, "/top_view", {"px_per_m", "max_range_m", "max_half_width_m"});
    // The top view may not exceed 16 Mpx (48 MB per frame): a typo in px_per_m must not
    // exhaust memory.
    const double px = c.top_view.px_per_m * c.top_view.px_per_m * c.top_view.max_range_m * 2.0 *
                      c.top_view.max_half_width_m;
    if (px > 16e6)
      result.errors.push_back("/top_view: px_per_m^2 * max_range_m * 2 max_half_width_m = " +
                              Json(std::round(px)).dump() + " px, above 16 Mpx");
  }
  if (const Json* m = r.section(root, "marker")) {
    const std::string p = "/marker";
    r.read(*m, p, "size_m", c.marker.size_m, 0.01, 10.0);
    r.read(*m, p, "cr_threshold", c.marker.cr_threshold, 0, 255);
    r.read(*m, p, "open_px", c.marker.open_px, 0, 51);
    r.read(*m, p, "close_px", c.marker.close_px, 0, 51);
    r.read(*m, p, "approx_epsilon", c.marker.approx_epsilon, 0.001, 0.5);
    r.read(*m, p, "size_tolerance", c.marker.size_tolerance, 0.0, 1.0);
    r.read(*m, p, "min_fill", c.marker.min_fill, 0.0, 1.0);
    r.read(*m, p, "template_px", c.marker.template_px, 4, 256);
    r.read(*m, p, "template_margin_px", c.marker.template_margin_px, 1, 256);
    r.read(*m, p, "min_score", c.marker.min_score, -1.0, 1.0);
    r.unknown(*m, p,
              {"size_m", "cr_threshold", "open_px", "close_px", "approx_epsilon", "size_tolerance",
               "min_fill", "template_px", "template_margin_px", "min_score"});
  }
  if (const Json* l = r.section(root, "light")) {
    const std::string p = "/light";
    r.read(*l, p, "darken", c.light.darken, 0, 255);
    r.read(*l, p, "threshold", c.light.threshold, 0, 255);
    r.read(*l, p, "erode_px", c.light.erode_px, 0, 51);
    r.read(*l, p, "dilate_px", c.light.dilate_px, 0, 101);
    r.read(*l, p, "min_area_m2", c.light.min_area_m2, 0.0, 100.0);
    r.unknown(*l, p, {"darken", "threshold", "erode_px", "dilate_px", "min_area_m2"});
  }
  r.unknown(root, "", {"top_view", "marker", "light"});
  return result;
}

Json visionConfigToJson(const VisionConfig& c) {
  Json o;
  o["top_view"] = {{"px_per_m", c.top_view.px_per_m},
                   {"max_range_m", c.top_view.max_range_m},
                   {"max_half_width_m", c.top_view.max_half_width_m}};
  o["marker"] = {{"size_m", c.marker.size_m},
                 {"cr_threshold", c.marker.cr_threshold},
                 {"open_px", c.marker.open_px},
                 {"close_px", c.marker.close_px},
                 {"approx_epsilon", c.marker.approx_epsilon},
                 {"size_tolerance", c.marker.size_tolerance},
                 {"min_fill", c.marker.min_fill},
                 {"template_px", c.marker.template_px},
                 {"template_margin_px", c.marker.template_margin_px},
                 {"min_score", c.marker.min_score}};
  o["light"] = {{"darken", c.light.darken},
                {"threshold", c.light.threshold},
                {"erode_px", c.light.erode_px},
                {"dilate_px", c.light.dilate_px},
                {"min_area_m2", c.light.min_area_m2}};
  return o;
}

}  // namespace irgs::vision
