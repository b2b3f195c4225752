#pragma once
// The text layout of saved map files: pretty, deterministic JSON that keeps short arrays and
// flat objects on one line. Internal to the map file writer.

#include <string>

#include <nlohmann/json.hpp>

namespace irgs::map_file_internal {

// `root` as text ending in a newline, nested blocks indented by two spaces, lines kept within
// 100 columns where a block fits. Throws std::invalid_argument for a non-finite number.
std::string layoutJson(const nlohmann::ordered_json& root);

}  // namespace irgs::map_file_internal
