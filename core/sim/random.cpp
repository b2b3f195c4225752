#include "core/sim/random.hpp"

#include <cmath>
#include <limits>

namespace irgs {

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

SimRandom SimRandom::stream(std::uint64_t seed, std::uint64_t purpose) {
  return SimRandom(splitMix64(seed ^ splitMix64(purpose)));
}

double SimRandom::uniform() {
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double SimRandom::gaussian() {
  // Marsaglia polar method: (u, v) uniform in the unit disc, s = u² + v²; then
  // u * sqrt(-2 ln s / s) and v * sqrt(-2 ln s / s) are two independent N(0, 1) samples.
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * portableLog(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor;
}

double portableLog(double x) {
  if (std::isnan(x) || x < 0.0)
    return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0)
    return -std::numeric_limits<double>::infinity();
  if (std::isinf(x))
    return x;
  // x = m * 2^e with m in [0.5, 1) (frexp is exact); move m into [sqrt(1/2), sqrt(2)).
  int e = 0;
  double m = std::frexp(x, &e);
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    --e;
  }
  // ln m = 2 atanh(f), f = (m - 1) / (m + 1), |f| < 0.1716: the odd series
  // 2 (f + f³/3 + f⁵/5 + ...) converges below 1e-17 relative after the f^23 term.
  const double f = (m - 1.0) / (m + 1.0);
  const double f2 = f * f;
  double sum = 0.0;
  for (int k = 23; k >= 3; k -= 2)
    sum = (sum + 1.0 / k) * f2;
  const double ln_m = 2.0 * f + 2.0 * f * sum;
  // ln 2 split into a high part exact in products with small integers and a low correction.
  constexpr double kLn2Hi = 6.93147180369123816490e-01;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  const double de = static_cast<double>(e);
  return de * kLn2Hi + (ln_m + de * kLn2Lo);
}

}  // namespace irgs
