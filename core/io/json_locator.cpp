#include "core/io/json_locator.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>

namespace irgs {
namespace {

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// Index just past the string starting at `pos` (which holds '"'), or npos when unterminated.
std::size_t skipString(std::string_view text, std::size_t pos) {
  for (std::size_t i = pos + 1; i < text.size(); ++i) {
    if (text[i] == '\\')
      ++i;
    else if (text[i] == '"')
      return i + 1;
  }
  return std::string_view::npos;
}

std::string decodeKey(std::string_view token) {
  // token includes the quotes
  const std::string_view inner = token.substr(1, token.size() - 2);
  if (inner.find('\\') == std::string_view::npos)
    return std::string(inner);
  try {
    return nlohmann::json::parse(token).get<std::string>();
  } catch (const std::exception&) {
    return std::string(inner);
  }
}

// The tolerant scanner. Calls record(pointer, offset) for every value start; stops at `stop` or
// at the first malformed token and returns the pointer of the value being read there. The
// pointer is maintained incrementally, so the scan is linear in the text for any nesting.
template <typename Record>
std::string scan(std::string_view text, std::size_t stop, Record&& record) {
  struct Frame {
    bool object = false;
    std::size_t index = 0;
    std::size_t base = 0;  // length of the container's own pointer
  };
  enum class Expect { kValue, kValueOrEnd, kKey, kKeyOrEnd, kColon, kCommaOrEnd, kDone };
  std::vector<Frame> frames;
  std::string path;  // pointer of the value being read (or of the innermost container)
  Expect expect = Expect::kValue;

  auto afterValue = [&] { expect = frames.empty() ? Expect::kDone : Expect::kCommaOrEnd; };
  auto close = [&] {
    path.resize(frames.back().base);
    frames.pop_back();
    afterValue();
  };
  auto enterElement = [&](Frame& f) {
    path.resize(f.base);
    path += '/';
    path += std::to_string(f.index);
  };

  std::size_t pos = 0;
  while (true) {
    while (pos < text.size() && isSpace(text[pos]))
      ++pos;
    if (pos >= text.size() || pos >= stop || expect == Expect::kDone)
      break;
    const char c = text[pos];
    switch (expect) {
      case Expect::kValueOrEnd:
        if (c == ']') {
          ++pos;
          close();
          continue;
        }
        [[fallthrough]];
      case Expect::kValue: {
        record(path, pos);
        if (c == '{') {
          frames.push_back({true, 0, path.size()});
          expect = Expect::kKeyOrEnd;
          ++pos;
        } else if (c == '[') {
          frames.push_back({false, 0, path.size()});
          enterElement(frames.back());
          expect = Expect::kValueOrEnd;
          ++pos;
        } else if (c == '"') {
          const std::size_t end = skipString(text, pos);
          if (end == std::string_view::npos)
            return path;
          pos = end;
          afterValue();
        } else if (c == ',' || c == ':' || c == '}' || c == ']') {
          return path;
        } else {
          while (pos < text.size() && !isSpace(text[pos]) && text[pos] != ',' && text[pos] != '}' &&
                 text[pos] != ']' && text[pos] != ':')
            ++pos;
          afterValue();
        }
        break;
      }
      case Expect::kKeyOrEnd:
        if (c == '}') {
          ++pos;
          close();
          continue;
        }
        [[fallthrough]];
      case Expect::kKey: {
        if (c != '"')
          return path;
        const std::size_t end = skipString(text, pos);
        if (end == std::string_view::npos)
          return path;
        path.resize(frames.back().base);
        path += '/';
        path += JsonLocator::escapeToken(decodeKey(text.substr(pos, end - pos)));
        pos = end;
        expect = Expect::kColon;
        break;
      }
      case Expect::kColon:
        if (c != ':')
          return path;
        ++pos;
        expect = Expect::kValue;
        break;
      case Expect::kCommaOrEnd: {
        Frame& f = frames.back();
        if (c == ',') {
          ++pos;
          if (f.object) {
            path.resize(f.base);
            expect = Expect::kKey;
          } else {
            ++f.index;
            enterElement(f);
            expect = Expect::kValue;
          }
        } else if ((c == '}' && f.object) || (c == ']' && !f.object)) {
          ++pos;
          close();
        } else {
          return path;
        }
        break;
      }
      case Expect::kDone:
        break;
    }
  }
  return path;
}

}  // namespace

JsonLocator::JsonLocator(std::string_view text) : text_(text) {
  line_starts_.push_back(0);
  for (std::size_t i = 0; i < text_.size(); ++i) {
    if (text_[i] == '\n')
      line_starts_.push_back(i + 1);
  }
  // Later duplicates win, as in nlohmann::json (the last of duplicate keys is kept).
  scan(text_, std::string_view::npos, [this](const std::string& pointer, std::size_t offset) {
    offsets_.insert_or_assign(pointer, offset);
  });
}

TextPosition JsonLocator::positionOf(std::size_t offset) const {
  offset = std::min(offset, text_.size());
  const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  const std::size_t line_index = static_cast<std::size_t>(it - line_starts_.begin()) - 1;
  int column = 1;
  for (std::size_t i = line_starts_[line_index]; i < offset; ++i) {
    // Count code points: skip UTF-8 continuation bytes.
    if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80)
      ++column;
  }
  return {static_cast<int>(line_index) + 1, column};
}

TextPosition JsonLocator::locate(std::string_view pointer) const {
  std::string p(pointer);
  while (true) {
    const auto it = offsets_.find(p);
    if (it != offsets_.end())
      return positionOf(it->second);
    if (p.empty())
      return text_.empty() ? TextPosition{} : positionOf(0);
    p.resize(p.rfind('/'));
  }
}

std::string JsonLocator::pointerAt(std::size_t offset) const {
  return pointerIn(text_, offset);
}

TextPosition JsonLocator::positionIn(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  TextPosition p{1, 1};
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++p.column;
    }
  }
  return p;
}

std::string JsonLocator::pointerIn(std::string_view text, std::size_t offset) {
  return scan(text, offset, [](const std::string&, std::size_t) {});
}

std::string JsonLocator::escapeToken(std::string_view key) {
  std::string out;
  out.reserve(key.size());
  for (const char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

NestingDepth maxNestingDepth(std::string_view text) {
  NestingDepth result;
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      const std::size_t end = skipString(text, i);
      if (end == std::string_view::npos)
        break;
      i = end - 1;
    } else if (c == '[' || c == '{') {
      if (++depth > result.depth)
        result = {depth, i};
    } else if (c == ']' || c == '}') {
      depth = std::max(0, depth - 1);
    }
  }
  return result;
}

}  // namespace irgs
