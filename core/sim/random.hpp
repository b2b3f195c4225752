#pragma once
// The simulator's random numbers, identical on every platform for a given seed.
//
// std::mt19937_64 is fully specified by the C++ standard, but the standard distributions are
// not (std::normal_distribution differs between libstdc++, libc++ and MSVC). So the
// distributions here are written out with IEEE-754 basic operations only (+ - * / sqrt, all
// correctly rounded): uniform from the top 53 bits, normal by Marsaglia's polar method with a
// logarithm computed by a fixed series instead of libm's log (whose last bit varies).

#include <cstdint>
#include <random>

namespace irgs {

class SimRandom {
 public:
  explicit SimRandom(std::uint64_t seed) : engine_(seed) {}

  // Independent stream for one purpose (motion, sonar, ...): the sequence of one purpose does
  // not change when another purpose draws more or fewer numbers.
  static SimRandom stream(std::uint64_t seed, std::uint64_t purpose);

  std::uint64_t bits() { return engine_(); }
  // Uniform in [0, 1), multiples of 2^-53.
  double uniform();
  // Standard normal N(0, 1).
  double gaussian();
  double gaussian(double mean, double stddev) { return mean + stddev * gaussian(); }
  // True with probability p (p <= 0: never, p >= 1: always).
  bool bernoulli(double p) { return uniform() < p; }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// Natural logarithm of x > 0 from basic operations only (within 2 ulp of the true value);
// deterministic across platforms. Returns -inf for 0 and NaN for negative or NaN input.
double portableLog(double x);

// SplitMix64 finaliser: a well-mixed 64-bit hash, used to derive stream seeds.
std::uint64_t splitMix64(std::uint64_t x);

}  // namespace irgs
