#include "core/io/pgm.hpp"

#include <cctype>
#include <limits>
#include <stdexcept>

#include "core/io/atomic_file.hpp"

namespace irgs {
namespace {

constexpr int kMaxMaxval = 65535;

// Header tokenizer: whitespace separated ASCII decimals, '#' starts a comment to end of line.
class HeaderReader {
 public:
  HeaderReader(std::string_view bytes, std::size_t pos) : bytes_(bytes), pos_(pos) {}

  std::size_t pos() const { return pos_; }
  int line() const { return line_; }
  int column() const { return static_cast<int>(pos_ - line_start_) + 1; }

  void skipSpaceAndComments() {
    while (pos_ < bytes_.size()) {
      const char c = bytes_[pos_];
      if (c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n')
          ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        advance();
      } else {
        return;
      }
    }
  }

  // Reads an unsigned decimal; nothing when the next byte is not a digit. `overflow` is set when
  // the value exceeds `limit`.
  std::optional<long long> readNumber(long long limit, bool& overflow) {
    overflow = false;
    if (pos_ >= bytes_.size() || !std::isdigit(static_cast<unsigned char>(bytes_[pos_])))
      return std::nullopt;
    long long value = 0;
    while (pos_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[pos_]))) {
      if (!overflow) {
        value = value * 10 + (bytes_[pos_] - '0');
        if (value > limit)
          overflow = true;
      }
      ++pos_;
    }
    return value;
  }

  bool atEnd() const { return pos_ >= bytes_.size(); }
  char peek() const { return bytes_[pos_]; }
  void advance() {
    if (bytes_[pos_] == '\n') {
      ++line_;
      line_start_ = pos_ + 1;
    }
    ++pos_;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_;
  int line_ = 1;
  std::size_t line_start_ = 0;
};

std::string describeByte(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (std::isprint(u))
    return std::string("'") + c + "'";
  static constexpr char kHex[] = "0123456789abcdef";
  return std::string("byte 0x") + kHex[u >> 4] + kHex[u & 15];
}

}  // namespace

PgmReadResult parsePgm(std::string_view bytes, const std::string& source_name) {
  PgmReadResult result;
  auto error = [&](int line, int column, std::string message) {
    result.diagnostics.push_back(
        {Severity::kError, source_name, line, column, {}, std::move(message)});
    return std::move(result);
  };

  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '2')) {
    return error(1, 1,
                 bytes.size() >= 2 && bytes[0] == 'P'
                     ? "unsupported Netpbm type P" + std::string(1, bytes[1]) +
                           " (only grey maps P5 and P2 are read)"
                     : "not a PGM image (expected the magic number P5 or P2)");
  }
  const bool binary = bytes[1] == '5';
  HeaderReader reader(bytes, 2);

  // width, height, maxval
  static constexpr const char* kFieldNames[] = {"width", "height", "maxval"};
  long long values[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const std::size_t before = reader.pos();
    reader.skipSpaceAndComments();
    if (reader.atEnd())
      return error(reader.line(), reader.column(),
                   std::string("file ends in the header before the ") + kFieldNames[i]);
    if (reader.pos() == before)
      return error(reader.line(), reader.column(),
                   std::string("expected whitespace before the ") + kFieldNames[i]);
    const int line = reader.line(), column = reader.column();
    bool overflow = false;
    const long long limit = i == 2 ? kMaxMaxval : std::numeric_limits<int>::max();
    const auto number = reader.readNumber(limit, overflow);
    if (!number)
      return error(line, column,
                   std::string("expected the ") + kFieldNames[i] + " as a decimal number, found " +
                       describeByte(reader.peek()));
    if (overflow || *number <= 0) {
      return error(line, column,
                   std::string(kFieldNames[i]) + " must be " +
                       (i == 2 ? "between 1 and 65535" : "a positive number that fits an int"));
    }
    values[i] = *number;
  }
  const long long width = values[0], height = values[1], maxval = values[2];

  // Exactly one whitespace byte separates maxval from the raster.
  if (reader.atEnd())
    return error(reader.line(), reader.column(), "file ends right after maxval: no pixel data");
  if (!std::isspace(static_cast<unsigned char>(reader.peek())))
    return error(reader.line(), reader.column(),
                 "expected whitespace after maxval, found " + describeByte(reader.peek()));
  reader.advance();

  const std::size_t available = bytes.size() - reader.pos();
  // Bound the pixel count by the data present before allocating: a P2 sample needs at least one
  // digit plus a separator, a P5 sample one or two bytes.
  const int sample_bytes = binary && maxval > 255 ? 2 : 1;
  const long double pixel_count =
      static_cast<long double>(width) * static_cast<long double>(height);
  if (binary && pixel_count * sample_bytes > static_cast<long double>(available)) {
    return error(0, 0,
                 "pixel data is truncated: a " + std::to_string(width) + " x " +
                     std::to_string(height) + " image with maxval " + std::to_string(maxval) +
                     " needs " +
                     std::to_string(static_cast<unsigned long long>(pixel_count * sample_bytes)) +
                     " bytes, the file has " + std::to_string(available));
  }
  if (!binary && pixel_count > static_cast<long double>(available / 2 + 1)) {
    return error(0, 0,
                 "pixel data is truncated: " + std::to_string(width) + " x " +
                     std::to_string(height) + " samples cannot fit in the " +
                     std::to_string(available) + " bytes left");
  }

  GrayImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  const auto count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  image.pixels.resize(count);
  const auto scale = [maxval](long long v) {
    return static_cast<std::uint8_t>((v * 255 + maxval / 2) / maxval);
  };

  if (binary) {
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + reader.pos());
    for (std::size_t i = 0; i < count; ++i) {
      const long long v = sample_bytes == 2 ? (static_cast<long long>(data[2 * i]) << 8) |
                                                  static_cast<long long>(data[2 * i + 1])
                                            : static_cast<long long>(data[i]);
      if (v > maxval) {
        const std::size_t col = i % static_cast<std::size_t>(width);
        const std::size_t row = i / static_cast<std::size_t>(width);
        return error(0, 0,
                     "sample " + std::to_string(v) + " at pixel (" + std::to_string(col) + ", " +
                         std::to_string(row) + ") exceeds maxval " + std::to_string(maxval));
      }
      image.pixels[i] = scale(v);
    }
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      reader.skipSpaceAndComments();
      if (reader.atEnd()) {
        return error(reader.line(), reader.column(),
                     "pixel data is truncated: found " + std::to_string(i) + " of " +
                         std::to_string(count) + " samples");
      }
      const int line = reader.line(), column = reader.column();
      bool overflow = false;
      const auto v = reader.readNumber(maxval, overflow);
      if (!v)
        return error(line, column, "expected a sample value, found " + describeByte(reader.peek()));
      if (overflow)
        return error(line, column, "sample exceeds maxval " + std::to_string(maxval));
      image.pixels[i] = scale(*v);
      if (!reader.atEnd() && !std::isspace(static_cast<unsigned char>(reader.peek())) &&
          reader.peek() != '#') {
        return error(reader.line(), reader.column(),
                     "expected whitespace after a sample, found " + describeByte(reader.peek()));
      }
    }
  }
  result.image = std::move(image);
  return result;
}

PgmReadResult readPgmFile(const std::filesystem::path& path) {
  const ReadFileResult file = readFile(path);
  if (!file.ok()) {
    PgmReadResult result;
    result.diagnostics.push_back({Severity::kError, path.string(), 0, 0, {}, file.error});
    return result;
  }
  return parsePgm(file.bytes, path.string());
}

std::string encodePgm(const GrayImage& image, std::string_view comment) {
  if (image.width <= 0 || image.height <= 0)
    throw std::invalid_argument("encodePgm: image dimensions must be positive");
  if (image.pixels.size() !=
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::invalid_argument("encodePgm: pixel count does not match width * height");
  std::string out = "P5\n";
  if (!comment.empty()) {
    // One comment line per input line; a comment cannot contain a newline.
    std::size_t start = 0;
    while (start <= comment.size()) {
      const std::size_t end = std::min(comment.find('\n', start), comment.size());
      out += "# ";
      out += comment.substr(start, end - start);
      out += '\n';
      start = end + 1;
    }
  }
  out += std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  out.append(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size());
  return out;
}

std::optional<std::string> writePgmFile(const GrayImage& image, const std::filesystem::path& path,
                                        std::string_view comment) {
  return writeFileAtomically(path, encodePgm(image, comment));
}

}  // namespace irgs
