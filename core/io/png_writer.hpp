#pragma once
// A small, dependency-free PNG encoder for screenshots and map exports.
//
// Output: signature, IHDR (8-bit, colour type grey/RGB/RGBA, no interlace), one IDAT holding a
// zlib stream of *stored* (uncompressed) deflate blocks with filter type 0 on every scanline,
// IEND. Files are larger than a compressing encoder's but every decoder reads them, and the
// encoder cannot fail.

#include <cstdint>
#include <span>
#include <string>

namespace irgs {

// Encodes `pixels` (row-major, row 0 at the top, `channels` bytes per pixel: 1 grey, 3 RGB,
// 4 RGBA) as PNG bytes. Throws std::invalid_argument for non-positive sizes, a channel count
// other than 1/3/4, or pixels.size() != width * height * channels.
std::string encodePng(int width, int height, int channels, std::span<const std::uint8_t> pixels);

// Checksums used by PNG, exposed for tests and other formats.
// CRC-32 (ISO 3309, polynomial 0xEDB88320 reflected); `crc` continues a previous result.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);
// Adler-32 (RFC 1950); `adler` continues a previous result (start with 1).
std::uint32_t adler32(std::span<const std::uint8_t> bytes, std::uint32_t adler = 1);

}  // namespace irgs
