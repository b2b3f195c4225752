#pragma once
// Typed access to the members of a parsed map document, each problem reported as a diagnostic
// located (line, column, JSON pointer) in the source text. Internal to the map file reader.

#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/io/diagnostic.hpp"
#include "core/io/json_locator.hpp"
#include "core/world/world_map.hpp"

namespace irgs::map_file_internal {

// A short description of a JSON value's type for messages ("a string", "null", ...).
std::string describe(const nlohmann::json& v);

// Collects diagnostics about one JSON text. Each accessor reports its own problem and returns
// nothing (nullptr, std::nullopt, false) so callers only test and skip.
class JsonFieldReader {
 public:
  using json = nlohmann::json;

  JsonFieldReader(std::string_view text, std::string source)
      : text_(text), source_(std::move(source)) {}

  std::string_view text() const { return text_; }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  std::vector<Diagnostic> takeDiagnostics() { return std::move(diagnostics_); }

  // --- diagnostics -------------------------------------------------------------------------
  // Adds a diagnostic found elsewhere (e.g. in a file this one refers to).
  void add(Diagnostic diagnostic) { diagnostics_.push_back(std::move(diagnostic)); }
  void report(Severity severity, const std::string& pointer, std::string message);
  void error(const std::string& pointer, std::string message) {
    report(Severity::kError, pointer, std::move(message));
  }
  void warning(const std::string& pointer, std::string message) {
    report(Severity::kWarning, pointer, std::move(message));
  }
  // Reports (as an error) nesting deeper than `max_depth`; false then. Run before parsing:
  // copying nested JSON recurses.
  bool checkNesting(int max_depth);
  // Reports a parse failure of the text, at the offending byte when the exception names it.
  void syntaxError(const nlohmann::json::exception& e);

  // --- typed access ------------------------------------------------------------------------
  bool expectObject(const json& v, const std::string& pointer, std::string_view what);
  // Member `key` of `obj`, or nullptr (reported when required).
  const json* member(const json& obj, const std::string& pointer, const char* key, bool required,
                     std::string_view hint = {});
  std::optional<double> number(const json& v, const std::string& pointer);
  // Optional number member with a default; nothing when present but invalid.
  std::optional<double> optionalNumber(const json& obj, const std::string& pointer, const char* key,
                                       double fallback);
  std::optional<double> positiveNumber(const json& obj, const std::string& pointer, const char* key,
                                       double fallback, const char* unit);
  std::optional<std::string> string(const json& v, const std::string& pointer);
  std::optional<bool> boolean(const json& obj, const std::string& pointer, const char* key,
                              bool fallback);
  std::optional<Vec2> point(const json& v, const std::string& pointer);
  std::optional<Vec2> pointMember(const json& obj, const std::string& pointer, const char* key);
  std::optional<std::vector<Vec2>> points(const json& v, const std::string& pointer);
  // The array member `key` of the root (absent = empty).
  const json* list(const json& root, const char* key);
  // Unknown members of obj (to keep); warns about those not marked as extensions with "x-".
  json extras(const json& obj, const std::string& pointer,
              std::initializer_list<std::string_view> known);
  // Optional "id": a string, unique within its list (`seen` maps id -> pointer of first use).
  std::optional<std::string> id(const json& obj, const std::string& pointer, bool required,
                                std::map<std::string, std::string>& seen);

 private:
  std::string_view text_;
  std::string source_;
  std::unique_ptr<JsonLocator> locator_;  // built on the first diagnostic
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace irgs::map_file_internal
