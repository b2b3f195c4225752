#pragma once
// Helpers shared by the map file reader and writer; not part of the public API (map_file.hpp).

#include <cstddef>
#include <string>
#include <string_view>

#include "core/io/json_locator.hpp"

namespace irgs::map_file_internal {

// The JSON pointer of member `key` (escaped) or element `index` below `pointer`.
inline std::string child(const std::string& pointer, std::string_view key) {
  return pointer + "/" + JsonLocator::escapeToken(key);
}
inline std::string child(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
}

inline std::string quote(std::string_view s) {
  return "'" + std::string(s) + "'";
}

}  // namespace irgs::map_file_internal
