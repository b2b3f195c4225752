// libFuzzer harness for the small human-written formats: robot profiles (JSON) and drive
// scripts (text). The first byte picks the parser. Invariants: never crash or throw; a result
// exactly when no error; a parsed script gives finite commands at any time.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/robot/robot_profile_file.hpp"
#include "core/sim/drive_script.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] & 1U) {
    const irgs::RobotProfileResult r = irgs::parseRobotProfileJson(rest, "fuzz-robot.json");
    IRGS_FUZZ_CHECK(r.profile.has_value() == !irgs::hasErrors(r.diagnostics));
  } else {
    const irgs::DriveScriptResult r = irgs::parseDriveScript(rest, "fuzz-script.txt");
    IRGS_FUZZ_CHECK(r.script.has_value() == !irgs::hasErrors(r.diagnostics));
    if (r.script) {
      for (const double t : {0.0, 1.0, r.script->lastTime_s(), r.script->lastTime_s() + 1.0}) {
        const irgs::VelocityCommand c = r.script->commandAt(t);
        IRGS_FUZZ_CHECK(std::isfinite(c.linear_mps) && std::isfinite(c.angular_radps));
      }
    }
  }
  return 0;
}
