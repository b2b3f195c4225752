#pragma once
// A plain 8-bit RGB image: the frame type every camera producer and consumer in IRGS shares.
// Core owns it so the renderer (core/camera), the OpenCV pipelines (core/vision) and the Qt
// panel (widgets/camera) exchange frames without depending on each other's libraries.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace irgs {

struct Rgb8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

// Row-major, interleaved R, G, B bytes; `stride` bytes per row (>= 3 * width).
struct RgbImage {
  int width = 0;
  int height = 0;
  int stride = 0;
  std::vector<std::uint8_t> data;

  RgbImage() = default;
  // A width x height image filled with `fill`. Throws std::invalid_argument for negative sizes.
  RgbImage(int w, int h, Rgb8 fill = {}) : width(w), height(h), stride(3 * w) {
    if (w < 0 || h < 0)
      throw std::invalid_argument("RgbImage: negative size");
    data.resize(static_cast<std::size_t>(stride) * static_cast<std::size_t>(h));
    for (std::size_t i = 0; i + 2 < data.size(); i += 3) {
      data[i] = fill.r;
      data[i + 1] = fill.g;
      data[i + 2] = fill.b;
    }
  }

  bool empty() const { return width == 0 || height == 0; }
  std::uint8_t* row(int y) { return data.data() + static_cast<std::ptrdiff_t>(y) * stride; }
  const std::uint8_t* row(int y) const {
    return data.data() + static_cast<std::ptrdiff_t>(y) * stride;
  }
  Rgb8 at(int x, int y) const {
    const std::uint8_t* p = row(y) + 3 * x;
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, Rgb8 c) {
    std::uint8_t* p = row(y) + 3 * x;
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }

  friend bool operator==(const RgbImage&, const RgbImage&) = default;
};

}  // namespace irgs
