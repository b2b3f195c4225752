#include "core/world/map_file_fields.hpp"

#include <algorithm>
#include <cmath>

#include "core/world/map_file_internal.hpp"

namespace irgs::map_file_internal {

using nlohmann::json;

std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

// --- diagnostics ---------------------------------------------------------------------------

void JsonFieldReader::report(Severity severity, const std::string& pointer, std::string message) {
  if (!locator_)
    locator_ = std::make_unique<JsonLocator>(text_);
  const TextPosition at = locator_->locate(pointer);
  diagnostics_.push_back({severity, source_, at.line, at.column, pointer, std::move(message)});
}

bool JsonFieldReader::checkNesting(int max_depth) {
  const NestingDepth depth = maxNestingDepth(text_);
  if (depth.depth <= max_depth)
    return true;
  // No full locator here: its table of pointers would grow with the square of the depth.
  const TextPosition at = JsonLocator::positionIn(text_, depth.offset);
  diagnostics_.push_back(
      {Severity::kError, source_, at.line, at.column, JsonLocator::pointerIn(text_, depth.offset),
       "values are nested deeper than " + std::to_string(max_depth) + " levels"});
  return false;
}

void JsonFieldReader::syntaxError(const nlohmann::json::exception& e) {
  locator_ = std::make_unique<JsonLocator>(text_);
  std::size_t offset = text_.size();
  std::string what = e.what();
  std::string reason = what;
  if (const auto* pe = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
    offset = pe->byte > 0 ? pe->byte - 1 : 0;
    // "[json.exception.parse_error.101] parse error at line 3, column 7: <reason>"
    if (const auto colon = what.find(": "); colon != std::string::npos)
      reason = what.substr(colon + 2);
  } else {
    // e.g. "[json.exception.out_of_range.406] number overflow parsing '1e400'"
    if (const auto bracket = what.find("] "); bracket != std::string::npos)
      reason = what.substr(bracket + 2);
    const auto open = what.find('\'');
    const auto close = what.rfind('\'');
    if (open != std::string::npos && close > open) {
      const auto at = text_.find(what.substr(open + 1, close - open - 1));
      if (at != std::string_view::npos)
        offset = at;
    }
    if (reason.find("number overflow") != std::string::npos)
      reason += " (numbers must be finite)";
  }
  const TextPosition at = locator_->positionOf(offset);
  diagnostics_.push_back({Severity::kError, source_, at.line, at.column,
                          locator_->pointerAt(offset), "invalid JSON: " + reason});
}

// --- typed access --------------------------------------------------------------------------

bool JsonFieldReader::expectObject(const json& v, const std::string& pointer,
                                   std::string_view what) {
  if (v.is_object())
    return true;
  error(pointer, "expected " + std::string(what) + " (an object), found " + describe(v));
  return false;
}

const json* JsonFieldReader::member(const json& obj, const std::string& pointer, const char* key,
                                    bool required, std::string_view hint) {
  const auto it = obj.find(key);
  if (it != obj.end())
    return &*it;
  if (required) {
    std::string message = std::string("missing required key '") + key + "'";
    if (!hint.empty())
      message += " (" + std::string(hint) + ")";
    error(child(pointer, key), std::move(message));
  }
  return nullptr;
}

std::optional<double> JsonFieldReader::number(const json& v, const std::string& pointer) {
  if (!v.is_number()) {
    error(pointer, "expected a number, found " + describe(v));
    return std::nullopt;
  }
  const double d = v.get<double>();
  if (!std::isfinite(d)) {
    error(pointer, "the number is not finite");
    return std::nullopt;
  }
  return d;
}

std::optional<double> JsonFieldReader::optionalNumber(const json& obj, const std::string& pointer,
                                                      const char* key, double fallback) {
  const json* v = member(obj, pointer, key, false);
  return v == nullptr ? std::optional<double>(fallback) : number(*v, child(pointer, key));
}

std::optional<double> JsonFieldReader::positiveNumber(const json& obj, const std::string& pointer,
                                                      const char* key, double fallback,
                                                      const char* unit) {
  auto v = optionalNumber(obj, pointer, key, fallback);
  if (v && !(*v > 0.0)) {
    error(child(pointer, key), std::string("must be a positive number of ") + unit);
    return std::nullopt;
  }
  return v;
}

std::optional<std::string> JsonFieldReader::string(const json& v, const std::string& pointer) {
  if (!v.is_string()) {
    error(pointer, "expected a string, found " + describe(v));
    return std::nullopt;
  }
  return v.get<std::string>();
}

std::optional<bool> JsonFieldReader::boolean(const json& obj, const std::string& pointer,
                                             const char* key, bool fallback) {
  const json* v = member(obj, pointer, key, false);
  if (v == nullptr)
    return fallback;
  if (!v->is_boolean()) {
    error(child(pointer, key), "expected true or false, found " + describe(*v));
    return std::nullopt;
  }
  return v->get<bool>();
}

std::optional<Vec2> JsonFieldReader::point(const json& v, const std::string& pointer) {
  if (!v.is_array() || v.size() != 2) {
    error(pointer,
          "expected a point [x, y] in metres, found " +
              (v.is_array() ? "an array of " + std::to_string(v.size()) + " values" : describe(v)));
    return std::nullopt;
  }
  const auto x = number(v[0], child(pointer, std::size_t{0}));
  const auto y = number(v[1], child(pointer, std::size_t{1}));
  if (!x || !y)
    return std::nullopt;
  return Vec2(*x, *y);
}

std::optional<Vec2> JsonFieldReader::pointMember(const json& obj, const std::string& pointer,
                                                 const char* key) {
  const json* v = member(obj, pointer, key, true, "[x, y] in metres");
  return v == nullptr ? std::nullopt : point(*v, child(pointer, key));
}

std::optional<std::vector<Vec2>> JsonFieldReader::points(const json& v,
                                                         const std::string& pointer) {
  if (!v.is_array()) {
    error(pointer, "expected an array of points [[x, y], ...], found " + describe(v));
    return std::nullopt;
  }
  std::vector<Vec2> out;
  bool ok = true;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (auto p = point(v[i], child(pointer, i)))
      out.push_back(*p);
    else
      ok = false;
  }
  return ok ? std::optional(std::move(out)) : std::nullopt;
}

const json* JsonFieldReader::list(const json& root, const char* key) {
  const json* v = member(root, "", key, false);
  if (v != nullptr && !v->is_array()) {
    error(child("", key), "expected an array, found " + describe(*v));
    return nullptr;
  }
  return v;
}

json JsonFieldReader::extras(const json& obj, const std::string& pointer,
                             std::initializer_list<std::string_view> known) {
  json out = json::object();
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (std::find(known.begin(), known.end(), it.key()) != known.end())
      continue;
    if (it.key().rfind("x-", 0) != 0)
      warning(child(pointer, it.key()), "unknown key " + quote(it.key()) + " is kept as it is");
    out[it.key()] = it.value();
  }
  return out;
}

std::optional<std::string> JsonFieldReader::id(const json& obj, const std::string& pointer,
                                               bool required,
                                               std::map<std::string, std::string>& seen) {
  const json* v = member(obj, pointer, "id", required);
  if (v == nullptr)
    return required ? std::nullopt : std::optional<std::string>(std::string());
  auto s = string(*v, child(pointer, "id"));
  if (!s)
    return std::nullopt;
  if (s->empty()) {
    if (required)
      error(child(pointer, "id"), "must not be empty");
    return required ? std::nullopt : s;
  }
  const auto [it, inserted] = seen.emplace(*s, pointer);
  if (!inserted) {
    error(child(pointer, "id"),
          "duplicate id " + quote(*s) + " (first used by " + it->second + ")");
    return std::nullopt;
  }
  return s;
}

}  // namespace irgs::map_file_internal
