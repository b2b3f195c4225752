#include "core/estimation/caster_profile.hpp"

#include <cmath>
#include <string>

namespace irgs {

namespace {

void addError(std::vector<Diagnostic>& out, const std::string& field, const std::string& message) {
  out.push_back({Severity::kError, "", 0, 0, field, message});
}

std::optional<double> readNumber(const nlohmann::json& object, const std::string& pointer,
                                 const char* key, std::vector<Diagnostic>& out) {
  const auto it = object.find(key);
  if (it == object.end()) {
    addError(out, pointer + "/" + key, "required number is missing");
    return std::nullopt;
  }
  if (!it->is_number() || !std::isfinite(it->get<double>())) {
    addError(out, pointer + "/" + key, "expected a finite number");
    return std::nullopt;
  }
  return it->get<double>();
}

}  // namespace

CasterGeometryResult casterGeometryFromProfile(const RobotProfile& profile) {
  CasterGeometryResult result;
  std::vector<Diagnostic>& out = result.diagnostics;
  if (profile.drive.type != DriveType::kThreeCaster)
    addError(out, "/drive/type", "expected \"three_caster\"");
  const std::string pointer = "/drive/three_caster";
  const auto it = profile.drive.extra.find("three_caster");
  if (it == profile.drive.extra.end() || !it->is_object()) {
    addError(out, pointer, "required object is missing");
    return result;
  }
  CasterDriveGeometry g;
  g.wheel_radius_m = profile.drive.wheel_radius_m;
  if (!(g.wheel_radius_m > 0.0) || !std::isfinite(g.wheel_radius_m))
    addError(out, "/drive/wheel_radius_m", "must be finite and > 0");
  if (const auto eps = readNumber(*it, pointer, "caster_offset_m", out)) {
    if (*eps > 0.0)
      g.offset_m = *eps;
    else
      addError(out, pointer + "/caster_offset_m", "must be > 0 (eps = 0 is not a caster)");
  }
  const auto casters = it->find("casters");
  if (casters == it->end() || !casters->is_array() || casters->size() != 3) {
    addError(out, pointer + "/casters", "expected an array of exactly 3 casters");
    return result;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string ptr = pointer + "/casters/" + std::to_string(i);
    const nlohmann::json& c = (*casters)[i];
    if (!c.is_object()) {
      addError(out, ptr, "expected an object {d_m, alpha_deg}");
      continue;
    }
    if (const auto d = readNumber(c, ptr, "d_m", out)) {
      if (*d >= 0.0)
        g.casters[i].d_m = *d;
      else
        addError(out, ptr + "/d_m", "must be >= 0");
    }
    if (const auto a = readNumber(c, ptr, "alpha_deg", out))
      g.casters[i].alpha_rad = degToRad(*a);
  }
  if (!hasErrors(out))
    result.geometry = g;
  return result;
}

}  // namespace irgs
