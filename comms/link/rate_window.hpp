#pragma once
// Sum of values added over the last `window_s` seconds, for per-second rates. Fixed storage:
// the window is split into kBuckets buckets, so the sum is exact to one bucket width
// (window_s / kBuckets) at the old edge. Time is the caller's (seconds, monotonic).

#include <array>
#include <cstdint>

namespace irgs::comms {

class RateWindow {
 public:
  static constexpr int kBuckets = 20;

  // Throws std::invalid_argument unless window_s is finite and > 0.
  explicit RateWindow(double window_s = 2.0);

  void add(double now_s, double amount);
  // Sum over buckets no older than the window at now_s.
  double sum(double now_s) const;
  // sum / window_s.
  double ratePerSecond(double now_s) const;
  double windowSeconds() const { return window_s_; }
  void clear();

 private:
  struct Bucket {
    std::int64_t index = -1;  // floor(time / bucket width); -1 = never used
    double value = 0.0;
  };
  std::int64_t indexOf(double now_s) const;

  double window_s_;
  double bucket_s_;
  std::array<Bucket, kBuckets> buckets_{};
};

}  // namespace irgs::comms
