#pragma once
// Netpbm grey-map (PGM) reading and writing: the image half of a ROS map_server map.
//
// Reads binary P5 and plain-text P2, with '#' comments anywhere in the header, any whitespace
// between header fields and maxval 1..65535 (16-bit samples are big-endian in P5); samples are
// scaled to 8 bit as round(v * 255 / maxval). Writes binary P5 with maxval 255.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/diagnostic.hpp"

namespace irgs {

// An 8-bit grey image, row 0 at the top as stored in the file.
struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height, row-major

  std::uint8_t at(int col, int row) const {
    return pixels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(col)];
  }
};

struct PgmReadResult {
  std::optional<GrayImage> image;  // empty whenever diagnostics hold an error
  std::vector<Diagnostic> diagnostics;
};

// Decodes PGM bytes. `source_name` is only used in diagnostics. Header problems are located by
// line and column; a short pixel block says how many bytes/samples were expected and found.
PgmReadResult parsePgm(std::string_view bytes, const std::string& source_name);
PgmReadResult readPgmFile(const std::filesystem::path& path);

// Encodes P5, maxval 255. Throws std::invalid_argument when pixels.size() != width * height or a
// dimension is not positive.
std::string encodePgm(const GrayImage& image, std::string_view comment = {});
// Encodes and writes atomically; returns an error message on failure.
std::optional<std::string> writePgmFile(const GrayImage& image, const std::filesystem::path& path,
                                        std::string_view comment = {});

}  // namespace irgs
