#include "app/robot/arrival_rate_meter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace irgs::app {

ArrivalRateMeter::ArrivalRateMeter(double window_s) : window_s_(window_s) {
  if (!std::isfinite(window_s) || !(window_s > 0.0))
    throw std::invalid_argument("ArrivalRateMeter: window must be > 0");
}

void ArrivalRateMeter::record(double arrival_s) {
  ++count_;
  if (!first_s_)
    first_s_ = arrival_s;
  last_s_ = std::max(last_s_, arrival_s);
  recent_.push_back(arrival_s);
  while (!recent_.empty() && recent_.front() <= arrival_s - window_s_)
    recent_.pop_front();
  peak_ = std::max(peak_, static_cast<std::uint32_t>(recent_.size()));
}

double ArrivalRateMeter::meanPerSecond() const {
  if (count_ < 2 || !first_s_ || !(last_s_ > *first_s_))
    return 0.0;
  return static_cast<double>(count_) / (last_s_ - *first_s_);
}

std::string ArrivalRateMeter::summary() const {
  char text[128];
  std::snprintf(text, sizeof text, "%llu in %.1f s (%.1f/s), peak %u in %g s",
                static_cast<unsigned long long>(count_), first_s_ ? last_s_ - *first_s_ : 0.0,
                meanPerSecond(), peak_, window_s_);
  return text;
}

}  // namespace irgs::app
