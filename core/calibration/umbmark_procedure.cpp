#include "core/calibration/umbmark_procedure.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/calibration/profile_calibration.hpp"

namespace irgs {

double UmbmarkProcedureResult::improvement() const {
  if (!verification || !verification->ok || verification->e_max_syst_m <= 0.0)
    return std::numeric_limits<double>::infinity();
  return analysis.e_max_syst_m / verification->e_max_syst_m;
}

namespace {

UmbmarkProcedureResult analyse(const RobotProfile& profile, std::vector<UmbmarkRun> runs,
                               double side_m) {
  UmbmarkProcedureResult result;
  result.runs = std::move(runs);
  result.analysis = analyseUmbmark(result.runs, {side_m, profile.drive.wheelbase_m});
  result.diagnostics = result.analysis.diagnostics;
  result.corrected = profile;
  if (result.analysis.ok) {
    result.corrected = applyUmbmark(profile, result.analysis, side_m);
    result.ok = true;
  }
  return result;
}

}  // namespace

UmbmarkProcedureResult runUmbmarkProcedureInSimulator(const RobotProfile& profile,
                                                      const UmbmarkInjection& injection,
                                                      const UmbmarkRunConfig& config, bool verify) {
  const UmbmarkSimulation before = runUmbmarkInSimulator(profile, injection, profile, config);
  UmbmarkProcedureResult result = analyse(profile, before.runs(), config.side_m);
  result.diagnostics.insert(result.diagnostics.begin(), before.diagnostics.begin(),
                            before.diagnostics.end());
  result.trials = before.trials;
  if (!result.ok || !verify)
    return result;
  UmbmarkRunConfig again = config;
  again.seed = config.seed + 1;  // another day on the same floor
  const UmbmarkSimulation after =
      runUmbmarkInSimulator(profile, injection, result.corrected, again);
  for (const std::string& d : after.diagnostics)
    result.diagnostics.push_back("verification: " + d);
  result.verification =
      analyseUmbmark(after.runs(), {config.side_m, result.corrected.drive.wheelbase_m});
  result.verification_trials = after.trials;
  return result;
}

UmbmarkProcedureResult analyseMeasuredUmbmark(const RobotProfile& profile,
                                              std::span<const UmbmarkRun> runs, double side_m) {
  if (!std::isfinite(side_m) || side_m <= 0.0)
    throw std::invalid_argument("analyseMeasuredUmbmark: side must be > 0");
  return analyse(profile, std::vector<UmbmarkRun>(runs.begin(), runs.end()), side_m);
}

UmbmarkRunsText parseUmbmarkRuns(const std::string& text) {
  UmbmarkRunsText out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
      continue;
    std::string fields[3];
    std::istringstream row(line);
    int n = 0;
    for (std::string field; n < 4 && std::getline(row, field, ','); ++n) {
      if (n < 3) {
        const auto a = field.find_first_not_of(" \t\r");
        const auto b = field.find_last_not_of(" \t\r");
        fields[n] = a == std::string::npos ? std::string() : field.substr(a, b - a + 1);
      }
    }
    const std::string where = "line " + std::to_string(number) + ": ";
    if (n != 3) {
      out.diagnostics.push_back(where + "expected \"cw|ccw, x_m, y_m\"");
      continue;
    }
    UmbmarkRun run;
    if (fields[0] == "cw") {
      run.direction = UmbmarkDirection::kClockwise;
    } else if (fields[0] == "ccw") {
      run.direction = UmbmarkDirection::kCounterClockwise;
    } else {
      out.diagnostics.push_back(where + "direction must be cw or ccw, not \"" + fields[0] + "\"");
      continue;
    }
    try {
      std::size_t ux = 0, uy = 0;
      const double x = std::stod(fields[1], &ux);
      const double y = std::stod(fields[2], &uy);
      if (ux != fields[1].size() || uy != fields[2].size() || !std::isfinite(x) ||
          !std::isfinite(y))
        throw std::invalid_argument("not a number");
      run.error_m = Vec2(x, y);
    } catch (const std::exception&) {
      out.diagnostics.push_back(where + "x and y must be numbers (metres)");
      continue;
    }
    out.runs.push_back(run);
  }
  return out;
}

}  // namespace irgs
