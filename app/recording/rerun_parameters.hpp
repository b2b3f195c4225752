#pragma once
// The parameters a re-run may change (docs/gui.md, "Re-run with parameters"): the mapper's
// (grid resolution, sonar valid distance, inverse sensor model) and the estimator's (which one,
// its gates and noise values, whether the map is built on its estimate). Each has a name (the
// irgs-rerun --param name and the recording's meta key "param.<name>"), a unit, a description
// and a default taken from the code's own defaults. Pure: no Qt.

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/estimation/estimator_runner.hpp"
#include "core/mapping/occupancy_grid.hpp"

namespace irgs::recording {

struct RerunParameters {
  double grid_resolution_m = 0.01;
  double sonar_valid_distance_m = 0.0;  // 0: each sonar's max range
  SonarInverseModel sensor_model;
  // The estimator run on the samples; nullopt: none (the robot's odometry is the pose, as the
  // session's map and trail use it).
  std::optional<EstimatorKind> estimator;
  bool map_on_estimate = false;  // integrate sonar on the estimate instead of the odometry
  EstimatorRunnerConfig estimator_config;

  std::optional<double> validDistance() const {
    return sonar_valid_distance_m > 0.0 ? std::optional<double>(sonar_valid_distance_m)
                                        : std::nullopt;
  }
};

enum class RerunParameterGroup { kMapping, kLocalization };

struct RerunParameterInfo {
  std::string name;  // "grid_resolution_m"
  std::string label;
  std::string unit;  // "" for counts and choices
  std::string description;
  RerunParameterGroup group = RerunParameterGroup::kMapping;
  std::vector<std::string> choices;  // non-empty: a choice (text), else a number
  double min = 0.0;                  // numbers only
  double max = 0.0;
};

inline constexpr char kRerunMetaPrefix[] = "param.";

// Every parameter, in display order.
const std::vector<RerunParameterInfo>& rerunParameters();
const RerunParameterInfo* findRerunParameter(std::string_view name);

// The value as text ("0.01", "ekf", "none", "1").
std::string rerunParameterValue(const RerunParameters& parameters, std::string_view name);
// Sets one parameter from text. Returns why not (unknown name, not a number, out of range,
// unknown choice); `parameters` is unchanged then.
std::optional<std::string> setRerunParameter(RerunParameters& parameters, std::string_view name,
                                             std::string_view value);
// "name=value" (the command line form).
std::optional<std::string> setRerunParameterAssignment(RerunParameters& parameters,
                                                       std::string_view assignment);

// The parameters a recording was made with: the defaults, overridden by its meta keys
// "param.<name>" (written by the ground station at the start of the session and when the
// mapping parameters change). Unusable values are skipped, each with a warning.
RerunParameters recordedRerunParameters(const std::map<std::string, std::string>& meta,
                                        std::vector<std::string>* warnings = nullptr);

// The names whose values differ between a and b.
std::vector<std::string> changedRerunParameters(const RerunParameters& a, const RerunParameters& b);

}  // namespace irgs::recording
