#include "core/io/png_writer.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace irgs {
namespace {

std::uint32_t readU32(const std::string& s, std::size_t at) {
  return (static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at])) << 24) |
         (static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 1])) << 16) |
         (static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 2])) << 8) |
         static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 3]));
}

// Bit-by-bit CRC-32, independent of the table-driven one under test.
std::uint32_t slowCrc32(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFU;
  for (const char ch : bytes) {
    c ^= static_cast<std::uint8_t>(ch);
    for (int k = 0; k < 8; ++k)
      c = (c >> 1) ^ (0xEDB88320U & (0U - (c & 1U)));
  }
  return ~c;
}

std::uint32_t slowAdler32(const std::string& bytes) {
  std::uint64_t a = 1, b = 0;
  for (const char ch : bytes) {
    a = (a + static_cast<std::uint8_t>(ch)) % 65521;
    b = (b + a) % 65521;
  }
  return static_cast<std::uint32_t>((b << 16) | a);
}

struct Chunk {
  std::string type;
  std::string data;
};

// Splits a PNG into chunks, checking the signature and every CRC.
std::vector<Chunk> readChunks(const std::string& png) {
  std::vector<Chunk> chunks;
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    const std::uint32_t len = readU32(png, at);
    EXPECT_LE(at + 12 + len, png.size());
    Chunk chunk{png.substr(at + 4, 4), png.substr(at + 8, len)};
    EXPECT_EQ(readU32(png, at + 8 + len), slowCrc32(chunk.type + chunk.data))
        << "CRC of chunk " << chunk.type;
    chunks.push_back(std::move(chunk));
    at += 12 + len;
  }
  EXPECT_EQ(at, png.size()) << "trailing bytes after the last chunk";
  return chunks;
}

// Inflates a zlib stream that contains only stored blocks.
std::string inflateStored(const std::string& zlib) {
  EXPECT_GE(zlib.size(), 6U);
  const auto cmf = static_cast<std::uint8_t>(zlib[0]), flg = static_cast<std::uint8_t>(zlib[1]);
  EXPECT_EQ(cmf & 0x0F, 8) << "compression method must be deflate";
  EXPECT_EQ((cmf * 256 + flg) % 31, 0) << "FCHECK";
  EXPECT_EQ(flg & 0x20, 0) << "no preset dictionary";
  std::string out;
  std::size_t at = 2;
  bool final_block = false;
  while (!final_block) {
    const auto header = static_cast<std::uint8_t>(zlib.at(at));
    final_block = (header & 1) != 0;
    EXPECT_EQ((header >> 1) & 3, 0) << "only stored blocks expected";
    const unsigned len = static_cast<std::uint8_t>(zlib.at(at + 1)) |
                         (static_cast<unsigned>(static_cast<std::uint8_t>(zlib.at(at + 2))) << 8);
    const unsigned nlen = static_cast<std::uint8_t>(zlib.at(at + 3)) |
                          (static_cast<unsigned>(static_cast<std::uint8_t>(zlib.at(at + 4))) << 8);
    EXPECT_EQ(len ^ 0xFFFFU, nlen);
    out += zlib.substr(at + 5, len);
    at += 5 + len;
  }
  EXPECT_EQ(readU32(zlib, at), slowAdler32(out));
  EXPECT_EQ(at + 4, zlib.size());
  return out;
}

struct Decoded {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, colour_type = 0;
  std::string scanlines;
};

Decoded decode(const std::string& png) {
  const std::vector<Chunk> chunks = readChunks(png);
  Decoded d;
  if (chunks.size() < 3)
    return d;
  EXPECT_EQ(chunks.front().type, "IHDR");
  EXPECT_EQ(chunks.back().type, "IEND");
  EXPECT_TRUE(chunks.back().data.empty());
  const std::string& ihdr = chunks.front().data;
  EXPECT_EQ(ihdr.size(), 13U);
  d.width = readU32(ihdr, 0);
  d.height = readU32(ihdr, 4);
  d.bit_depth = static_cast<std::uint8_t>(ihdr[8]);
  d.colour_type = static_cast<std::uint8_t>(ihdr[9]);
  EXPECT_EQ(ihdr.substr(10), std::string(3, '\0'));
  std::string zlib;
  for (std::size_t i = 1; i + 1 < chunks.size(); ++i) {
    EXPECT_EQ(chunks[i].type, "IDAT");
    zlib += chunks[i].data;
  }
  d.scanlines = inflateStored(zlib);
  return d;
}

std::string expectedScanlines(int width, int height, int channels,
                              const std::vector<std::uint8_t>& pixels) {
  std::string out;
  const std::size_t row = static_cast<std::size_t>(width * channels);
  for (int y = 0; y < height; ++y) {
    out += '\0';
    out.append(reinterpret_cast<const char*>(pixels.data()) + static_cast<std::size_t>(y) * row,
               row);
  }
  return out;
}

std::vector<std::uint8_t> pattern(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = static_cast<std::uint8_t>((i * 31 + i / 7) & 0xFF);
  return v;
}

TEST(PngWriter, ChecksumsMatchPublishedValues) {
  const std::string text = "123456789";
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(text.data()),
                                            text.size());
  EXPECT_EQ(crc32(bytes), 0xCBF43926U);    // the standard CRC-32 check value
  EXPECT_EQ(adler32(bytes), 0x091E01DEU);  // Adler-32 of "123456789"
  const std::string wiki = "Wikipedia";
  EXPECT_EQ(adler32({reinterpret_cast<const std::uint8_t*>(wiki.data()), wiki.size()}),
            0x11E60398U);
  // Continuing a checksum equals computing it in one go.
  EXPECT_EQ(crc32(bytes.subspan(4), crc32(bytes.first(4))), crc32(bytes));
  EXPECT_EQ(adler32(bytes.subspan(4), adler32(bytes.first(4))), adler32(bytes));
}

TEST(PngWriter, GreyImageDecodesToTheSameScanlines) {
  const auto pixels = pattern(5 * 3);
  const Decoded d = decode(encodePng(5, 3, 1, pixels));
  EXPECT_EQ(d.width, 5U);
  EXPECT_EQ(d.height, 3U);
  EXPECT_EQ(d.bit_depth, 8);
  EXPECT_EQ(d.colour_type, 0);
  EXPECT_EQ(d.scanlines, expectedScanlines(5, 3, 1, pixels));
}

TEST(PngWriter, RgbAndRgbaUseTheirColourTypes) {
  const auto rgb = pattern(4 * 2 * 3);
  const Decoded d3 = decode(encodePng(4, 2, 3, rgb));
  EXPECT_EQ(d3.colour_type, 2);
  EXPECT_EQ(d3.scanlines, expectedScanlines(4, 2, 3, rgb));
  const auto rgba = pattern(1 * 1 * 4);
  const Decoded d4 = decode(encodePng(1, 1, 4, rgba));
  EXPECT_EQ(d4.colour_type, 6);
  EXPECT_EQ(d4.scanlines, expectedScanlines(1, 1, 4, rgba));
}

TEST(PngWriter, LargeImageSpansManyStoredBlocksAndIdatChunks) {
  // 700 x 600 RGBA = 1.68 MB raw: 26 stored blocks and two IDAT chunks.
  const int w = 700, h = 600;
  const auto pixels = pattern(static_cast<std::size_t>(w * h * 4));
  const std::string png = encodePng(w, h, 4, pixels);
  std::size_t idats = 0;
  for (const Chunk& c : readChunks(png))
    idats += c.type == "IDAT" ? 1 : 0;
  EXPECT_GE(idats, 2U);
  const Decoded d = decode(png);
  EXPECT_EQ(d.scanlines, expectedScanlines(w, h, 4, pixels));
}

TEST(PngWriter, OutputIsDeterministic) {
  const auto pixels = pattern(9 * 9);
  EXPECT_EQ(encodePng(9, 9, 1, pixels), encodePng(9, 9, 1, pixels));
}

TEST(PngWriter, MisuseThrows) {
  const auto pixels = pattern(12);
  EXPECT_THROW(encodePng(0, 3, 1, pixels), std::invalid_argument);
  EXPECT_THROW(encodePng(2, 2, 2, pixels), std::invalid_argument);
  EXPECT_THROW(encodePng(2, 2, 1, pixels), std::invalid_argument);  // 12 != 4
  EXPECT_NO_THROW(encodePng(2, 2, 3, pixels));
}

}  // namespace
}  // namespace irgs
