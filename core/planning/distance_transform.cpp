#include "core/planning/distance_transform.hpp"

#include <stdexcept>

namespace irgs {
namespace {

// 1-D squared distance transform of f over n samples with stride (Felzenszwalb-Huttenlocher,
// Algorithm 1): d[q] = min_p ((q - p)^2 + f[p]). v/z/out are scratch of size n, n+1, n.
void transform1d(double* f, std::size_t n, std::size_t stride, std::vector<std::size_t>& v,
                 std::vector<double>& z, std::vector<double>& out) {
  // Samples at kNoSource never form part of the envelope; skipping them keeps the arithmetic
  // exact (differences against 1e300 would lose all precision).
  std::size_t k = 0;
  bool any = false;
  for (std::size_t q = 0; q < n; ++q) {
    const double fq = f[q * stride];
    if (fq >= kNoSource)
      continue;
    if (!any) {
      v[0] = q;
      z[0] = -kNoSource;
      z[1] = kNoSource;
      any = true;
      continue;
    }
    const double dq = static_cast<double>(q);
    // z[0] = -kNoSource is below every intersection, so the loop stops at k = 0 at the latest.
    double s = 0.0;
    for (;;) {
      const double dp = static_cast<double>(v[k]);
      s = ((fq + dq * dq) - (f[v[k] * stride] + dp * dp)) / (2.0 * (dq - dp));
      if (s > z[k])
        break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kNoSource;
  }
  if (!any)
    return;  // whole line without a source: stays kNoSource
  k = 0;
  for (std::size_t q = 0; q < n; ++q) {
    const double dq = static_cast<double>(q);
    while (z[k + 1] < dq)
      ++k;
    const double d = dq - static_cast<double>(v[k]);
    out[q] = d * d + f[v[k] * stride];
  }
  for (std::size_t q = 0; q < n; ++q)
    f[q * stride] = out[q];
}

}  // namespace

std::vector<double> squaredDistanceTransform(const std::vector<std::uint8_t>& source, int width,
                                             int height) {
  if (width < 0 || height < 0)
    throw std::invalid_argument("squaredDistanceTransform: negative size");
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  if (source.size() != w * h)
    throw std::invalid_argument("squaredDistanceTransform: source size does not match");
  std::vector<double> d(source.size(), kNoSource);
  for (std::size_t i = 0; i < source.size(); ++i)
    if (source[i] != 0)
      d[i] = 0.0;
  const std::size_t n = w > h ? w : h;
  std::vector<std::size_t> v(n + 1);
  std::vector<double> z(n + 2), out(n + 1);
  for (std::size_t col = 0; col < w; ++col)  // columns: along rows
    transform1d(d.data() + col, h, w, v, z, out);
  for (std::size_t row = 0; row < h; ++row)  // then rows
    transform1d(d.data() + row * w, w, 1, v, z, out);
  return d;
}

}  // namespace irgs
