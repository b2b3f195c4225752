#include "widgets/canvas/grid_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace irgs::widgets {
namespace {

int lerpChannel(int a, int b, double t) {
  return static_cast<int>(std::lround(a + (b - a) * t));
}

QRgb blend(const QColor& a, const QColor& b, double t, int alpha) {
  return qPremultiply(qRgba(lerpChannel(a.red(), b.red(), t), lerpChannel(a.green(), b.green(), t),
                            lerpChannel(a.blue(), b.blue(), t), alpha));
}

}  // namespace

QImage gridToImage(const OccupancyGrid& grid, const OccupancyGrid::CellRect& cells) {
  if (cells.empty())
    return {};
  const long long width = static_cast<long long>(cells.col1) - cells.col0 + 1;
  const long long height = static_cast<long long>(cells.row1) - cells.row0 + 1;
  // A QImage is limited to 2^31 bytes; a rect that large is a bug upstream, not a picture.
  if (width * height * 4 >= (1LL << 31))
    return {};

  // Colour by probability p = 1 / (1 + exp(-l)), through a table over the log-odds so the loop
  // does no exp(); kLutRange covers any sensible clamp (p beyond it is 0 or 1 to 3 decimals).
  constexpr int kLutSize = 1024;
  constexpr float kLutRange = 8.0f;  // log-odds in [-8, 8]
  static const std::array<QRgb, kLutSize> lut = [] {
    std::array<QRgb, kLutSize> table{};
    for (int i = 0; i < kLutSize; ++i) {
      const double l = (2.0 * i / (kLutSize - 1) - 1.0) * kLutRange;
      const double p = 1.0 / (1.0 + std::exp(-l));
      // Confident cells take the end colours; the ramp between stays for uncertain ones.
      const double t =
          std::clamp((p - kGridFreeBelow) / (kGridOccupiedAbove - kGridFreeBelow), 0.0, 1.0);
      table[static_cast<std::size_t>(i)] =
          blend(kGridFreeColour, kGridOccupiedColour, t * t * (3.0 - 2.0 * t), 255);
    }
    return table;
  }();

  std::vector<float> log_odds;
  grid.copyLogOdds(cells, log_odds);  // row-major from (col0, row0), NaN = never observed
  QImage image(static_cast<int>(width), static_cast<int>(height),
               QImage::Format_ARGB32_Premultiplied);
  const auto w = static_cast<std::size_t>(width);
  for (int y = 0; y < image.height(); ++y) {
    auto* line = reinterpret_cast<QRgb*>(image.scanLine(y));
    // Image row 0 is the top = the largest row (largest y).
    const float* src = log_odds.data() + static_cast<std::size_t>(image.height() - 1 - y) * w;
    for (std::size_t x = 0; x < w; ++x) {
      const float l = src[x];
      if (std::isnan(l)) {
        line[x] = 0;  // transparent
        continue;
      }
      const float t = (std::clamp(l, -kLutRange, kLutRange) / kLutRange + 1.0f) * 0.5f;
      line[x] = lut[static_cast<std::size_t>(t * (kLutSize - 1) + 0.5f)];
    }
  }
  return image;
}

QImage rasterToImage(const RasterMap& raster) {
  if (raster.empty() || raster.cells.size() != static_cast<std::size_t>(raster.width) *
                                                   static_cast<std::size_t>(raster.height))
    return {};
  QImage image(raster.width, raster.height, QImage::Format_ARGB32_Premultiplied);
  const QRgb unknown = qPremultiply(qRgba(150, 156, 166, 70));
  const QColor occupied(58, 63, 74);
  const QColor free(255, 255, 255);
  for (int y = 0; y < raster.height; ++y) {
    auto* line = reinterpret_cast<QRgb*>(image.scanLine(y));
    const int row = raster.height - 1 - y;
    for (int col = 0; col < raster.width; ++col) {
      const int v = raster.at(col, row);
      if (v < 0 || v > 100) {
        line[col] = unknown;
      } else if (v == 0) {
        line[col] = 0;  // free: the floor shows through
      } else {
        const double t = v / 100.0;
        line[col] = blend(free, occupied, t, static_cast<int>(std::lround(255.0 * t)));
      }
    }
  }
  return image;
}

}  // namespace irgs::widgets
