#include "core/calibration/profile_calibration.hpp"

#include <cmath>
#include <stdexcept>
#include <system_error>

#include "core/robot/robot_profile_file.hpp"

namespace irgs {

namespace {

constexpr const char* kCalibration = "calibration";

const nlohmann::json* section(const RobotProfile& profile, const char* name) {
  const auto c = profile.extra.find(kCalibration);
  if (c == profile.extra.end() || !c->is_object())
    return nullptr;
  const auto s = c->find(name);
  return s == c->end() ? nullptr : &*s;
}

// A finite number at `key`, or `fallback` when absent; nothing when present but unusable.
std::optional<double> number(const nlohmann::json& o, const char* key, double fallback) {
  const auto it = o.find(key);
  if (it == o.end())
    return fallback;
  if (!it->is_number())
    return std::nullopt;
  const double v = it->get<double>();
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

nlohmann::json& calibrationObject(RobotProfile& profile) {
  nlohmann::json& c = profile.extra[kCalibration];
  if (!c.is_object())
    c = nlohmann::json::object();
  return c;
}

}  // namespace

ProfileOdometry profileOdometry(const RobotProfile& profile) {
  ProfileOdometry result;
  result.odometry.wheelbase_m = profile.drive.wheelbase_m;
  const nlohmann::json* o = section(profile, "odometry");
  if (o == nullptr)
    return result;
  if (!o->is_object()) {
    result.error = "calibration.odometry is not an object";
    return result;
  }
  const auto left = number(*o, "left_wheel_scale", 1.0);
  const auto right = number(*o, "right_wheel_scale", 1.0);
  if (!left || !right || *left <= 0.0 || *right <= 0.0) {
    result.error = "calibration.odometry wheel scales must be numbers > 0; ignored";
    return result;
  }
  result.odometry.left_wheel_scale = *left;
  result.odometry.right_wheel_scale = *right;
  return result;
}

std::optional<GyroCalibration> profileGyroCalibration(const RobotProfile& profile) {
  const nlohmann::json* o = section(profile, "gyro");
  if (o == nullptr || !o->is_object())
    return std::nullopt;
  const auto c0 = number(*o, "bias_c0_dps", 0.0), c1 = number(*o, "bias_c1_dps_per_c", 0.0),
             c2 = number(*o, "bias_c2_dps_per_c2", 0.0), a1 = number(*o, "sf_a1", 0.0),
             a2 = number(*o, "sf_a2_per_dps", 0.0), a3 = number(*o, "sf_a3_per_dps2", 0.0);
  if (!c0 || !c1 || !c2 || !a1 || !a2 || !a3)
    return std::nullopt;
  GyroCalibration g;
  g.bias = {*c0, *c1, *c2};
  g.scale.a1 = *a1;
  g.scale.a2_per_dps = *a2;
  g.scale.a3_per_dps2 = *a3;
  return g;
}

RobotProfile applyUmbmark(const RobotProfile& profile, const UmbmarkAnalysis& analysis,
                          double side_m) {
  if (!analysis.ok)
    throw std::invalid_argument("applyUmbmark: the analysis failed; nothing to apply");
  const OdometryCorrection corrected = correctOdometry(
      profileOdometry(profile).odometry, analysis.wheel_diameter_ratio, analysis.wheelbase_ratio);
  RobotProfile out = profile;
  out.drive.wheelbase_m = corrected.wheelbase_m;
  calibrationObject(out)["odometry"] = {{"method", "UMBmark"},
                                        {"left_wheel_scale", corrected.left_wheel_scale},
                                        {"right_wheel_scale", corrected.right_wheel_scale},
                                        {"wheel_diameter_ratio", analysis.wheel_diameter_ratio},
                                        {"wheelbase_ratio", analysis.wheelbase_ratio},
                                        {"side_m", side_m},
                                        {"runs", analysis.cw_runs + analysis.ccw_runs},
                                        {"e_max_syst_m", analysis.e_max_syst_m},
                                        {"previous_wheelbase_m", profile.drive.wheelbase_m}};
  return out;
}

RobotProfile applyGyroCalibration(const RobotProfile& profile, const GyroCalibration& c) {
  const double values[] = {c.bias.c0_dps, c.bias.c1_dps_per_c, c.bias.c2_dps_per_c2,
                           c.scale.a1,    c.scale.a2_per_dps,  c.scale.a3_per_dps2};
  for (double v : values)
    if (!std::isfinite(v))
      throw std::invalid_argument("applyGyroCalibration: non-finite coefficient");
  RobotProfile out = profile;
  calibrationObject(out)["gyro"] = {{"bias_c0_dps", c.bias.c0_dps},
                                    {"bias_c1_dps_per_c", c.bias.c1_dps_per_c},
                                    {"bias_c2_dps_per_c2", c.bias.c2_dps_per_c2},
                                    {"sf_a1", c.scale.a1},
                                    {"sf_a2_per_dps", c.scale.a2_per_dps},
                                    {"sf_a3_per_dps2", c.scale.a3_per_dps2}};
  return out;
}

std::optional<std::string> saveCalibratedProfile(const RobotProfile& profile,
                                                 const std::filesystem::path& path) {
  if (path.empty())
    return std::string("no output file given");
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
      return "cannot create folder " + path.parent_path().string() + ": " + ec.message();
  }
  if (const auto error = saveRobotProfileFile(profile, path))
    return error->message;
  return std::nullopt;
}

}  // namespace irgs
