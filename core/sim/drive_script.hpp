#pragma once
// A timed teleoperation script: what to command, and from when. Used by the headless runner
// and by golden scenario tests (map + script + seed -> final pose).
//
// Text format, one command per line:
//
//   # a comment: from '#' to the end of the line, anywhere
//   0.0   drive 0.20 0      # TIME_S drive V_MPS OMEGA_DEGPS  (forward speed, turn rate CCW)
//   5.0   drive 0.10 30
//   12.5  stop              # TIME_S stop  (= drive 0 0)
//
// TIME_S is simulated time in seconds (>= 0); times never decrease. A command holds from its
// time until the next line's time; before the first line the robot is stopped, after the last
// the last command holds. Two lines with the same time: the later one wins. Blank lines are
// allowed. Turn rates are in degrees per second (people write the file); commands hold radians.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/diagnostic.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

struct DriveScriptStep {
  double time_s = 0.0;
  VelocityCommand command;
  int line = 0;  // 1-based source line, 0 when built in code
};

class DriveScript {
 public:
  DriveScript() = default;
  // Throws std::invalid_argument when a time is negative, not finite or decreasing.
  explicit DriveScript(std::vector<DriveScriptStep> steps);

  // The command in force at simulated time t_s.
  VelocityCommand commandAt(double t_s) const;

  const std::vector<DriveScriptStep>& steps() const { return steps_; }
  bool empty() const { return steps_.empty(); }
  // Time of the last line (0 for an empty script).
  double lastTime_s() const { return steps_.empty() ? 0.0 : steps_.back().time_s; }

 private:
  std::vector<DriveScriptStep> steps_;
};

struct DriveScriptResult {
  std::optional<DriveScript> script;    // present when there is no error
  std::vector<Diagnostic> diagnostics;  // with line and column

  bool ok() const { return script.has_value(); }
};

DriveScriptResult parseDriveScript(std::string_view text, const std::string& source_name);
DriveScriptResult loadDriveScriptFile(const std::filesystem::path& path);

}  // namespace irgs
