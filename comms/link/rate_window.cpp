#include "comms/link/rate_window.hpp"

#include <cmath>
#include <stdexcept>

namespace irgs::comms {

RateWindow::RateWindow(double window_s) : window_s_(window_s), bucket_s_(window_s / kBuckets) {
  if (!std::isfinite(window_s) || window_s <= 0.0)
    throw std::invalid_argument("RateWindow: window must be a positive number of seconds");
}

std::int64_t RateWindow::indexOf(double now_s) const {
  if (!std::isfinite(now_s) || now_s < 0.0)
    return 0;
  return static_cast<std::int64_t>(std::floor(now_s / bucket_s_));
}

void RateWindow::add(double now_s, double amount) {
  const std::int64_t index = indexOf(now_s);
  auto& bucket = buckets_[static_cast<std::size_t>(index % kBuckets)];
  if (bucket.index != index) {
    bucket.index = index;
    bucket.value = 0.0;
  }
  bucket.value += amount;
}

double RateWindow::sum(double now_s) const {
  const std::int64_t newest = indexOf(now_s);
  double total = 0.0;
  for (const auto& bucket : buckets_) {
    if (bucket.index >= 0 && bucket.index <= newest && newest - bucket.index < kBuckets)
      total += bucket.value;
  }
  return total;
}

double RateWindow::ratePerSecond(double now_s) const {
  return sum(now_s) / window_s_;
}

void RateWindow::clear() {
  buckets_.fill(Bucket{});
}

}  // namespace irgs::comms
