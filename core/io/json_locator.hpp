#pragma once
// Line/column positions for JSON values, which nlohmann::json does not keep.
//
// The locator tokenises the text once and records where every value starts, keyed by its JSON
// pointer (RFC 6901: "/walls/3/points/0"). Parsers look values up when they report a problem.
// The scan is tolerant: on malformed text it records what it could read and stops, so it can
// also name the value being read at a syntax error (pointerAt).

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace irgs {

struct TextPosition {
  int line = 0;    // 1-based, 0 = unknown
  int column = 0;  // 1-based, counted in characters (UTF-8 code points), a tab counts as one

  friend bool operator==(const TextPosition&, const TextPosition&) = default;
};

class JsonLocator {
 public:
  explicit JsonLocator(std::string_view text);

  // Start of the value at `pointer` ("" is the whole document). When the value does not exist
  // (a missing key) the position of its nearest existing ancestor is returned, which is the
  // object the key is missing from. {0, 0} only for an empty document.
  TextPosition locate(std::string_view pointer) const;
  // Position of byte `offset` (0-based); offsets past the end map to the end of the text.
  TextPosition positionOf(std::size_t offset) const;
  // Pointer of the innermost value being read when the scanner reaches byte `offset`: the place
  // a syntax error at that offset belongs to ("" at top level).
  std::string pointerAt(std::size_t offset) const;

  // The same two answers straight from a text, without building a locator (whose table of every
  // value's pointer can be large for hostile, deeply nested input). Linear in `offset`.
  static TextPosition positionIn(std::string_view text, std::size_t offset);
  static std::string pointerIn(std::string_view text, std::size_t offset);

  // Escapes one reference token for a JSON pointer ("~" -> "~0", "/" -> "~1").
  static std::string escapeToken(std::string_view key);

 private:
  std::string text_;
  std::vector<std::size_t> line_starts_;
  std::unordered_map<std::string, std::size_t> offsets_;
};

// Deepest nesting of arrays/objects in `text` (strings are skipped) and the byte offset where
// that depth is first reached; guards recursive consumers against hostile input.
struct NestingDepth {
  int depth = 0;
  std::size_t offset = 0;
};
NestingDepth maxNestingDepth(std::string_view text);

}  // namespace irgs
