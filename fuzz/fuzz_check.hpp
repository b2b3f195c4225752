#pragma once
// Invariant checks for the fuzz harnesses: a broken invariant aborts, which libFuzzer (and the
// corpus replay runner) reports as a crash with the input that caused it.

#include <cstdio>
#include <cstdlib>

#define IRGS_FUZZ_CHECK(condition)                                                                 \
  do {                                                                                             \
    if (!(condition)) {                                                                            \
      std::fprintf(stderr, "fuzz invariant failed: %s (%s:%d)\n", #condition, __FILE__, __LINE__); \
      std::abort();                                                                                \
    }                                                                                              \
  } while (false)
