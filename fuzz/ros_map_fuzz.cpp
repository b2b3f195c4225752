// libFuzzer harness for the ROS map_server YAML reader and the PGM decoder. The first byte picks
// which one gets the rest. Invariants: never crash or throw; a result exactly when no error.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/pgm.hpp"
#include "core/world/ros_map.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] & 1U) {
    const irgs::PgmReadResult r = irgs::parsePgm(rest, "fuzz.pgm");
    IRGS_FUZZ_CHECK(r.image.has_value() == !irgs::hasErrors(r.diagnostics));
    if (r.image) {
      IRGS_FUZZ_CHECK(r.image->pixels.size() == static_cast<std::size_t>(r.image->width) *
                                                    static_cast<std::size_t>(r.image->height));
    }
  } else {
    const irgs::RosMapLoadResult r = irgs::parseRosMap(rest, "fuzz.yaml", "/nonexistent-irgs-fuzz");
    IRGS_FUZZ_CHECK(r.raster.has_value() == !irgs::hasErrors(r.diagnostics));
  }
  return 0;
}
