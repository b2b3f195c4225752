#pragma once
// The whole UMBmark procedure as the wizard and irgs-calibrate run it: the runs (simulated with
// injected errors, or measured return errors from a real floor), the analysis, the corrected
// profile and, in the simulator, a verification re-run of the same physical robot on the
// corrected odometry. One function so the GUI and the command line give the same numbers.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/calibration/umbmark.hpp"
#include "core/calibration/umbmark_run.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct UmbmarkProcedureResult {
  bool ok = false;  // the analysis succeeded and `corrected` holds the corrections
  std::vector<std::string> diagnostics;
  std::vector<UmbmarkRun> runs;  // what was analysed
  UmbmarkAnalysis analysis;
  RobotProfile corrected;
  // Simulator only: the same physical robot re-run on the corrected odometry (another seed).
  std::optional<UmbmarkAnalysis> verification;
  // Simulator only: the runs with their true and believed paths, before and after correction.
  std::vector<UmbmarkTrial> trials;
  std::vector<UmbmarkTrial> verification_trials;
  // e_max before / after (infinity when no verification or a perfect after-run).
  double improvement() const;
};

// Simulator: runs config.runs_per_direction squares each way on `profile` with `injection`,
// analyses them, corrects the profile and (verify) re-runs with seed config.seed + 1.
// Throws what runUmbmarkInSimulator throws.
UmbmarkProcedureResult runUmbmarkProcedureInSimulator(const RobotProfile& profile,
                                                      const UmbmarkInjection& injection,
                                                      const UmbmarkRunConfig& config,
                                                      bool verify = true);

// A real floor: the return errors (measured true end - odometry end, start frame) of runs the
// robot drove on `profile`'s odometry. Throws std::invalid_argument for a side <= 0.
UmbmarkProcedureResult analyseMeasuredUmbmark(const RobotProfile& profile,
                                              std::span<const UmbmarkRun> runs, double side_m);

// Measured runs as text, one per line: "cw|ccw, x_m, y_m" (the return error); '#' comments and
// blank lines are skipped; unreadable lines give "line N: ..." diagnostics.
struct UmbmarkRunsText {
  std::vector<UmbmarkRun> runs;
  std::vector<std::string> diagnostics;
};
UmbmarkRunsText parseUmbmarkRuns(const std::string& text);

}  // namespace irgs
