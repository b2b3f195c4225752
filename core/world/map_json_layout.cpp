#include "core/world/map_json_layout.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs::map_file_internal {
namespace {

using OrderedJson = nlohmann::ordered_json;

constexpr std::size_t kLineWidth = 100;

std::string scalarText(const OrderedJson& v) {
  if (v.is_number_float() && !std::isfinite(v.get<double>()))
    throw std::invalid_argument("serializeMap: an unknown key holds a non-finite number");
  return v.dump(-1, ' ', false, OrderedJson::error_handler_t::replace);
}

std::string compactText(const OrderedJson& v) {
  if (!v.is_structured())
    return scalarText(v);
  std::string out(1, v.is_array() ? '[' : '{');
  bool first = true;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (!first)
      out += ", ";
    first = false;
    if (v.is_object())
      out += scalarText(OrderedJson(it.key())) + ": ";
    out += compactText(it.value());
  }
  out += v.is_array() ? ']' : '}';
  return out;
}

int nesting(const OrderedJson& v) {
  if (!v.is_structured())
    return 0;
  int deepest = 0;
  for (const auto& e : v)
    deepest = std::max(deepest, nesting(e));
  return deepest + 1;
}

bool holdsObject(const OrderedJson& v) {
  for (const auto& e : v) {
    if (e.is_object() || (e.is_array() && holdsObject(e)))
      return true;
  }
  return false;
}

// Writes v starting at column `column`, nested blocks indented by two spaces per level. Point
// lists ([[x, y], ...]) and objects without nested objects (a wall, a pose) stay on one line
// when they fit.
void prettyText(const OrderedJson& v, std::size_t indent, std::size_t column, std::string& out) {
  if (!v.is_structured() || v.empty()) {
    out += v.is_structured() ? (v.is_array() ? "[]" : "{}") : scalarText(v);
    return;
  }
  if (v.is_array() ? nesting(v) <= 2 : nesting(v) <= 3 && !holdsObject(v)) {
    const std::string c = compactText(v);
    if (column + c.size() + 1 <= kLineWidth) {
      out += c;
      return;
    }
  }
  const std::string pad(indent + 2, ' ');
  out += v.is_array() ? "[\n" : "{\n";
  bool first = true;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (!first)
      out += ",\n";
    first = false;
    out += pad;
    std::size_t at = pad.size();
    if (v.is_object()) {
      const std::string key = scalarText(OrderedJson(it.key())) + ": ";
      out += key;
      at += key.size();
    }
    prettyText(it.value(), indent + 2, at, out);
  }
  out += "\n" + std::string(indent, ' ') + (v.is_array() ? "]" : "}");
}

}  // namespace

std::string layoutJson(const OrderedJson& root) {
  std::string out;
  prettyText(root, 0, 0, out);
  out += '\n';
  return out;
}

}  // namespace irgs::map_file_internal
