#include "app/recording/rerun_parameters.hpp"

#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

namespace irgs::recording {
namespace {

using Getter = std::function<double(const RerunParameters&)>;
using Setter = std::function<void(RerunParameters&, double)>;

struct NumberAccess {
  Getter get;
  Setter set;
};

constexpr char kNone[] = "none";

struct Table {
  std::vector<RerunParameterInfo> infos;
  std::map<std::string, NumberAccess, std::less<>> numbers;
};

const Table& table() {
  static const Table t = [] {
    Table out;
    auto number = [&out](RerunParameterInfo info, Getter get, Setter set) {
      out.numbers[info.name] = {std::move(get), std::move(set)};
      out.infos.push_back(std::move(info));
    };
    using G = RerunParameterGroup;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    number(
        {"grid_resolution_m",
         "Grid resolution",
         "m",
         "Cell size of the sonar occupancy grid",
         G::kMapping,
         {},
         0.001,
         1.0},
        [](const RerunParameters& p) { return p.grid_resolution_m; },
        [](RerunParameters& p, double v) { p.grid_resolution_m = v; });
    number(
        {"sonar_valid_distance_m",
         "Sonar valid distance",
         "m",
         "Echoes farther than this count as no echo up to it (0: each sonar's max range)",
         G::kMapping,
         {},
         0.0,
         100.0},
        [](const RerunParameters& p) { return p.sonar_valid_distance_m; },
        [](RerunParameters& p, double v) { p.sonar_valid_distance_m = v; });
    number(
        {"free_log_odds",
         "Free increment",
         "log-odds",
         "Added to cells inside the cone before the echo",
         G::kMapping,
         {},
         -OccupancyGrid::kMaxAbsLogOdds,
         0.0},
        [](const RerunParameters& p) { return p.sensor_model.free_log_odds; },
        [](RerunParameters& p, double v) { p.sensor_model.free_log_odds = v; });
    number(
        {"occupied_log_odds",
         "Occupied increment",
         "log-odds",
         "Added to cells on the echo's arc",
         G::kMapping,
         {},
         0.0,
         OccupancyGrid::kMaxAbsLogOdds},
        [](const RerunParameters& p) { return p.sensor_model.occupied_log_odds; },
        [](RerunParameters& p, double v) { p.sensor_model.occupied_log_odds = v; });
    number(
        {"arc_thickness_m",
         "Arc thickness",
         "m",
         "Thickness of the occupied arc at the range",
         G::kMapping,
         {},
         0.0,
         1.0},
        [](const RerunParameters& p) { return p.sensor_model.arc_thickness_m; },
        [](RerunParameters& p, double v) { p.sensor_model.arc_thickness_m = v; });
    number(
        {"clamp_min",
         "Log-odds floor",
         "log-odds",
         "Cells never go below this",
         G::kMapping,
         {},
         -OccupancyGrid::kMaxAbsLogOdds,  // the grid's 16-bit cells hold no more
         0.0},
        [](const RerunParameters& p) { return p.sensor_model.clamp_min; },
        [](RerunParameters& p, double v) { p.sensor_model.clamp_min = v; });
    number(
        {"clamp_max",
         "Log-odds ceiling",
         "log-odds",
         "Cells never go above this",
         G::kMapping,
         {},
         0.0,
         OccupancyGrid::kMaxAbsLogOdds},
        [](const RerunParameters& p) { return p.sensor_model.clamp_max; },
        [](RerunParameters& p, double v) { p.sensor_model.clamp_max = v; });
    number(
        {"no_echo_free_range_m",
         "No-echo free range",
         "m",
         "A reading without echo clears free space up to this range (0: nothing)",
         G::kMapping,
         {},
         0.0,
         100.0},
        [](const RerunParameters& p) { return p.sensor_model.no_echo_free_range_m; },
        [](RerunParameters& p, double v) { p.sensor_model.no_echo_free_range_m = v; });

    RerunParameterInfo estimator{"estimator",
                                 "Estimator",
                                 "",
                                 "Localization run on the samples (none: the robot's odometry)",
                                 G::kLocalization,
                                 {kNone},
                                 0.0,
                                 0.0};
    for (EstimatorKind kind : kAllEstimatorKinds)
      estimator.choices.emplace_back(toString(kind));
    out.infos.push_back(std::move(estimator));
    number(
        {"map_on_estimate",
         "Map on the estimate",
         "0/1",
         "1: integrate sonar on the estimator's pose instead of the odometry",
         G::kLocalization,
         {},
         0.0,
         1.0},
        [](const RerunParameters& p) { return p.map_on_estimate ? 1.0 : 0.0; },
        [](RerunParameters& p, double v) { p.map_on_estimate = v >= 0.5; });
    number(
        {"eps1_m",
         "Gate eps1",
         "m",
         "Paper 000 (41): corner/edge match radius",
         G::kLocalization,
         {},
         0.0,
         10.0},
        [](const RerunParameters& p) { return p.estimator_config.ekf.eps1_m; },
        [](RerunParameters& p, double v) { p.estimator_config.ekf.eps1_m = v; });
    number(
        {"eps2_deg",
         "Gate eps2",
         "deg",
         "Paper 000 (42): wall angle window",
         G::kLocalization,
         {},
         0.0,
         180.0},
        [](const RerunParameters& p) { return radToDeg(p.estimator_config.ekf.eps2_rad); },
        [](RerunParameters& p, double v) { p.estimator_config.ekf.eps2_rad = degToRad(v); });
    number(
        {"gate",
         "Mahalanobis gate g",
         "",
         "Paper 000 (49): updates with v^2/S above g are rejected (inf: no gate)",
         G::kLocalization,
         {},
         0.0,
         kInf},
        [](const RerunParameters& p) { return p.estimator_config.ekf.gate; },
        [](RerunParameters& p, double v) { p.estimator_config.ekf.gate = v; });
    number(
        {"sigma_d_m",
         "Range noise sigma_d",
         "m",
         "Stereo range measurement noise",
         G::kLocalization,
         {},
         1e-6,
         10.0},
        [](const RerunParameters& p) { return std::sqrt(p.estimator_config.ekf.r_d_m2); },
        [](RerunParameters& p, double v) { p.estimator_config.ekf.r_d_m2 = v * v; });
    number(
        {"sigma_theta_deg",
         "Bearing noise sigma_theta",
         "deg",
         "Stereo bearing measurement noise",
         G::kLocalization,
         {},
         1e-4,
         90.0},
        [](const RerunParameters& p) {
          return radToDeg(std::sqrt(p.estimator_config.ekf.r_theta_rad2));
        },
        [](RerunParameters& p, double v) {
          p.estimator_config.ekf.r_theta_rad2 = degToRad(v) * degToRad(v);
        });
    number(
        {"wheel_variance_per_m",
         "Process noise (wheel variance)",
         "m^2/m",
         "Variance of each wheel's travel per metre driven",
         G::kLocalization,
         {},
         0.0,
         1.0},
        [](const RerunParameters& p) { return p.estimator_config.process.wheel_variance_per_m; },
        [](RerunParameters& p, double v) { p.estimator_config.process.wheel_variance_per_m = v; });
    number(
        {"stereo_period_s",
         "Stereo firing period",
         "s",
         "Each stereo sensor fires once per period (000: 40 ms)",
         G::kLocalization,
         {},
         0.001,
         10.0},
        [](const RerunParameters& p) { return p.estimator_config.stereo_period_s; },
        [](RerunParameters& p, double v) { p.estimator_config.stereo_period_s = v; });
    return out;
  }();
  return t;
}

std::string formatNumber(double v) {
  if (std::isinf(v))
    return v > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out.precision(10);
  out << v;
  return out.str();
}

std::optional<double> parseNumber(std::string_view text) {
  if (text == "inf")
    return std::numeric_limits<double>::infinity();
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || std::isnan(v))
    return std::nullopt;
  return v;
}

}  // namespace

const std::vector<RerunParameterInfo>& rerunParameters() {
  return table().infos;
}

const RerunParameterInfo* findRerunParameter(std::string_view name) {
  for (const RerunParameterInfo& info : table().infos) {
    if (info.name == name)
      return &info;
  }
  return nullptr;
}

std::string rerunParameterValue(const RerunParameters& parameters, std::string_view name) {
  if (name == "estimator")
    return parameters.estimator ? toString(*parameters.estimator) : kNone;
  const auto it = table().numbers.find(name);
  return it == table().numbers.end() ? std::string() : formatNumber(it->second.get(parameters));
}

std::optional<std::string> setRerunParameter(RerunParameters& parameters, std::string_view name,
                                             std::string_view value) {
  const RerunParameterInfo* info = findRerunParameter(name);
  if (info == nullptr)
    return "unknown parameter '" + std::string(name) + "'";
  if (name == "estimator") {
    if (value == kNone) {
      parameters.estimator.reset();
      return std::nullopt;
    }
    const auto kind = parseEstimatorKind(value);
    if (!kind)
      return "estimator: '" + std::string(value) +
             "' is not one of none, dr, ekf, encoder-gyro, mouse";
    parameters.estimator = *kind;
    return std::nullopt;
  }
  const auto number = parseNumber(value);
  if (!number)
    return info->name + ": '" + std::string(value) + "' is not a number";
  if (*number < info->min || *number > info->max)
    return info->name + ": " + std::string(value) + " is outside [" + formatNumber(info->min) +
           ", " + formatNumber(info->max) + "] " + info->unit;
  table().numbers.find(name)->second.set(parameters, *number);
  return std::nullopt;
}

std::optional<std::string> setRerunParameterAssignment(RerunParameters& parameters,
                                                       std::string_view assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    return "'" + std::string(assignment) + "' is not name=value";
  return setRerunParameter(parameters, assignment.substr(0, eq), assignment.substr(eq + 1));
}

RerunParameters recordedRerunParameters(const std::map<std::string, std::string>& meta,
                                        std::vector<std::string>* warnings) {
  RerunParameters parameters;
  const std::string prefix = kRerunMetaPrefix;
  for (const auto& [key, value] : meta) {
    if (key.rfind(prefix, 0) != 0)
      continue;
    const auto error = setRerunParameter(parameters, key.substr(prefix.size()), value);
    if (error && warnings != nullptr)
      warnings->push_back("recorded parameter " + key + " skipped: " + *error);
  }
  return parameters;
}

std::vector<std::string> changedRerunParameters(const RerunParameters& a,
                                                const RerunParameters& b) {
  std::vector<std::string> changed;
  for (const RerunParameterInfo& info : table().infos) {
    if (rerunParameterValue(a, info.name) != rerunParameterValue(b, info.name))
      changed.push_back(info.name);
  }
  return changed;
}

}  // namespace irgs::recording
