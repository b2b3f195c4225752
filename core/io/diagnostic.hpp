#pragma once
// A problem found while reading a file or an argument, located as precisely as the format
// allows. Parsers return these as values; callers decide how to show them.

#include <string>
#include <vector>

namespace irgs {

enum class Severity { kWarning, kError };

struct Diagnostic {
  Severity severity = Severity::kError;
  std::string file;     // path or source name as given by the caller
  int line = 0;         // 1-based; 0 when unknown
  int column = 0;       // 1-based; 0 when unknown
  std::string field;    // JSON pointer or key path ("/walls/3/points"), empty when not a field
  std::string message;  // what is wrong and, where possible, what was expected

  // "file:line:column: error: field: message" (parts omitted when unknown).
  std::string toString() const {
    std::string out = file;
    if (line > 0)
      out += ":" + std::to_string(line);
    if (line > 0 && column > 0)
      out += ":" + std::to_string(column);
    out += severity == Severity::kError ? ": error: " : ": warning: ";
    if (!field.empty())
      out += field + ": ";
    out += message;
    return out;
  }
};

inline bool hasErrors(const std::vector<Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics) {
    if (d.severity == Severity::kError)
      return true;
  }
  return false;
}

}  // namespace irgs
