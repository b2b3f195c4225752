// libFuzzer harness for the JSON map parser. Invariants: never crash or throw; a map comes back
// exactly when there is no error (never half-loaded); a loaded map serialises and reloads.
//
//   build-fuzz/fuzz/irgs_fuzz_map_file -max_total_time=60 fuzz/corpus/map_file

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/world/map_file.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const irgs::MapLoadResult r = irgs::parseMapJson(text, "fuzz.json", "/nonexistent-irgs-fuzz");
  IRGS_FUZZ_CHECK(r.map.has_value() == !irgs::hasErrors(r.diagnostics));
  if (r.map) {
    const std::string saved = irgs::serializeMap(*r.map);
    const irgs::MapLoadResult again =
        irgs::parseMapJson(saved, "fuzz-resaved.json", "/nonexistent-irgs-fuzz");
    IRGS_FUZZ_CHECK(again.map.has_value() || r.map->raster.has_value());
  }
  return 0;
}
