#include "comms/robot/arcos_params.hpp"

#include <cmath>

namespace irgs::comms {

namespace {

// Reads a positive finite number; leaves `out` alone (and warns) otherwise.
void readPositive(const nlohmann::json& arcos, const char* key, double& out,
                  std::vector<std::string>& warnings) {
  if (!arcos.contains(key))
    return;
  const nlohmann::json& v = arcos.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0.0) {
    warnings.push_back(std::string("arcos.") + key + ": must be a positive number; using " +
                       std::to_string(out));
    return;
  }
  out = v.get<double>();
}

}  // namespace

ArcosParamsResult arcosParamsFromProfile(const RobotProfile& profile) {
  ArcosParamsResult result;
  if (!profile.extra.is_object() || !profile.extra.contains("arcos"))
    return result;
  const nlohmann::json& arcos = profile.extra.at("arcos");
  if (!arcos.is_object()) {
    result.warnings.push_back("arcos: must be an object; using the P3-DX defaults");
    return result;
  }
  result.found = true;
  ArcosParams& p = result.params;
  if (arcos.contains("subclass")) {
    if (arcos.at("subclass").is_string())
      p.subclass = arcos.at("subclass").get<std::string>();
    else
      result.warnings.push_back("arcos.subclass: must be a string");
  }
  readPositive(arcos, "angle_conv_factor", p.angle_conv_rad, result.warnings);
  readPositive(arcos, "dist_conv_factor", p.dist_conv_mm, result.warnings);
  readPositive(arcos, "vel_conv_factor", p.vel_conv_mmps, result.warnings);
  readPositive(arcos, "range_conv_factor", p.range_conv_mm, result.warnings);
  readPositive(arcos, "diff_conv_factor", p.diff_conv, result.warnings);
  double divisor = p.vel2_divisor;
  readPositive(arcos, "vel2_divisor", divisor, result.warnings);
  if (divisor != std::floor(divisor) || divisor > 1000.0)
    result.warnings.push_back("arcos.vel2_divisor: must be an integer 1-1000");
  else
    p.vel2_divisor = static_cast<int>(divisor);
  double cycle_ms = p.sip_cycle_s * 1000.0;
  readPositive(arcos, "sip_cycle_ms", cycle_ms, result.warnings);
  p.sip_cycle_s = cycle_ms / 1000.0;
  readPositive(arcos, "watchdog_s", p.watchdog_s, result.warnings);
  return result;
}

}  // namespace irgs::comms
