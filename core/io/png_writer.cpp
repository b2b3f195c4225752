#include "core/io/png_writer.hpp"

#include <array>
#include <stdexcept>
#include <string_view>

namespace irgs {
namespace {

constexpr std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k)
      c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}
constexpr auto kCrcTable = makeCrcTable();

// Largest payload of one stored deflate block (LEN is 16 bits).
constexpr std::size_t kMaxStoredBlock = 65535;

void putU32(std::string& out, std::uint32_t v) {
  out += static_cast<char>((v >> 24) & 0xFF);
  out += static_cast<char>((v >> 16) & 0xFF);
  out += static_cast<char>((v >> 8) & 0xFF);
  out += static_cast<char>(v & 0xFF);
}

std::span<const std::uint8_t> asBytes(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Appends length, type, data and the CRC over type + data.
void putChunk(std::string& out, std::string_view type, std::string_view data) {
  putU32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out += type;
  out += data;
  putU32(out, crc32(asBytes(std::string_view(out).substr(start))));
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  std::uint32_t c = crc ^ 0xFFFFFFFFU;
  for (const std::uint8_t b : bytes)
    c = kCrcTable[(c ^ b) & 0xFFU] ^ (c >> 8);
  return c ^ 0xFFFFFFFFU;
}

std::uint32_t adler32(std::span<const std::uint8_t> bytes, std::uint32_t adler) {
  constexpr std::uint32_t kMod = 65521;
  // 5552 is the largest run for which the sums cannot overflow 32 bits (zlib's NMAX).
  constexpr std::size_t kRun = 5552;
  std::uint32_t a = adler & 0xFFFFU, b = adler >> 16;
  std::size_t i = 0;
  while (i < bytes.size()) {
    const std::size_t end = std::min(bytes.size(), i + kRun);
    for (; i < end; ++i) {
      a += bytes[i];
      b += a;
    }
    a %= kMod;
    b %= kMod;
  }
  return (b << 16) | a;
}

std::string encodePng(int width, int height, int channels, std::span<const std::uint8_t> pixels) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("encodePng: width and height must be positive");
  if (channels != 1 && channels != 3 && channels != 4)
    throw std::invalid_argument("encodePng: channels must be 1 (grey), 3 (RGB) or 4 (RGBA)");
  const std::size_t row_bytes =
      static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  if (pixels.size() != row_bytes * static_cast<std::size_t>(height))
    throw std::invalid_argument(
        "encodePng: pixel buffer size does not match width * height * channels");

  // Raw scanlines: a filter-type byte (0 = none) before each row.
  std::string raw;
  raw.reserve((row_bytes + 1) * static_cast<std::size_t>(height));
  for (int row = 0; row < height; ++row) {
    raw += '\0';
    raw.append(
        reinterpret_cast<const char*>(pixels.data()) + static_cast<std::size_t>(row) * row_bytes,
        row_bytes);
  }

  // zlib stream (RFC 1950): CMF 0x78 (deflate, 32 KiB window), FLG 0x01 makes CMF*256+FLG a
  // multiple of 31; then stored deflate blocks (RFC 1951 3.2.4); then Adler-32 of the raw data.
  std::string zlib;
  zlib.reserve(raw.size() + raw.size() / kMaxStoredBlock * 5 + 16);
  zlib += static_cast<char>(0x78);
  zlib += static_cast<char>(0x01);
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min(kMaxStoredBlock, raw.size() - pos);
    const bool last = pos + len == raw.size();
    zlib += static_cast<char>(last ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
    zlib += static_cast<char>(len & 0xFF);
    zlib += static_cast<char>((len >> 8) & 0xFF);
    zlib += static_cast<char>(~len & 0xFF);
    zlib += static_cast<char>((~len >> 8) & 0xFF);
    zlib.append(raw, pos, len);
    pos += len;
  } while (pos < raw.size());
  putU32(zlib, adler32(asBytes(raw)));

  std::string ihdr;
  putU32(ihdr, static_cast<std::uint32_t>(width));
  putU32(ihdr, static_cast<std::uint32_t>(height));
  ihdr += static_cast<char>(8);                                          // bit depth
  ihdr += static_cast<char>(channels == 1 ? 0 : channels == 3 ? 2 : 6);  // colour type
  ihdr += std::string(3, '\0');  // compression, filter method, no interlace

  std::string png("\x89PNG\r\n\x1a\n", 8);
  putChunk(png, "IHDR", ihdr);
  // Several IDAT chunks keep each chunk far below the 2^31 - 1 length limit of PNG.
  constexpr std::size_t kIdatBytes = 1U << 20;
  for (std::size_t at = 0; at < zlib.size(); at += kIdatBytes)
    putChunk(png, "IDAT", std::string_view(zlib).substr(at, kIdatBytes));
  putChunk(png, "IEND", {});
  return png;
}

}  // namespace irgs
