#include "widgets/plots/plot_series.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs::widgets {

PlotSeries::PlotSeries(std::size_t capacity) : capacity_(capacity) {
  if (capacity == 0)
    throw std::invalid_argument("PlotSeries: capacity must be positive");
}

bool PlotSeries::append(double time_s, double value) {
  if (!std::isfinite(time_s) || !std::isfinite(value))
    return false;
  if (size_ > 0) {
    const double newest_s = newest().time_s;
    if (time_s < newest_s - kRestartGap_s)
      clear();
    else if (time_s < newest_s)
      return false;
  }
  if (size_ < capacity_) {
    if (buffer_.size() == buffer_.capacity())  // doubling, but never past the capacity
      buffer_.reserve(std::min(capacity_, std::max<std::size_t>(64, 2 * buffer_.size())));
    buffer_.push_back({time_s, value});
    ++size_;
  } else {
    buffer_[head_] = {time_s, value};
    head_ = (head_ + 1) % buffer_.size();
  }
  return true;
}

void PlotSeries::clear() {
  buffer_.clear();  // keeps the allocation
  head_ = 0;
  size_ = 0;
}

std::size_t PlotSeries::lowerBound(double time_s) const {
  std::size_t lo = 0;
  std::size_t hi = size_;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (at(mid).time_s < time_s)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

std::optional<PlotRange> PlotSeries::range(double t0, double t1) const {
  const std::size_t begin = lowerBound(t0);
  const std::size_t end = lowerBound(std::nextafter(t1, t1 + 1.0));
  if (begin >= end)
    return std::nullopt;
  PlotRange out{at(begin).value, at(begin).value};
  forEach(begin, end, [&out](const PlotSample& s) {
    out.min = std::min(out.min, s.value);
    out.max = std::max(out.max, s.value);
  });
  return out;
}

std::vector<PlotColumn> PlotSeries::decimate(double t0, double t1, int columns) const {
  std::vector<PlotColumn> out;
  if (columns <= 0 || !(t1 > t0))
    return out;
  const std::size_t begin = lowerBound(t0);
  const std::size_t end = lowerBound(std::nextafter(t1, t1 + 1.0));
  if (begin >= end)
    return out;
  const std::size_t count = end - begin;
  if (count <= static_cast<std::size_t>(columns)) {
    out.reserve(count);
    forEach(begin, end, [&out](const PlotSample& s) {
      out.push_back({s.time_s, s.value, s.value, s.value, s.value});
    });
    return out;
  }
  out.reserve(static_cast<std::size_t>(columns));
  const double per_s = columns / (t1 - t0);
  int current = -1;
  forEach(begin, end, [&](const PlotSample& s) {
    const int column = std::clamp(static_cast<int>((s.time_s - t0) * per_s), 0, columns - 1);
    if (column != current) {
      out.push_back({s.time_s, s.value, s.value, s.value, s.value});
      current = column;
      return;
    }
    PlotColumn& c = out.back();
    c.min = std::min(c.min, s.value);
    c.max = std::max(c.max, s.value);
    c.last = s.value;
  });
  return out;
}

std::vector<PlotSample> PlotSeries::samples(double t0, double t1) const {
  std::vector<PlotSample> out;
  forEach(lowerBound(t0), lowerBound(std::nextafter(t1, t1 + 1.0)),
          [&out](const PlotSample& s) { out.push_back(s); });
  return out;
}

}  // namespace irgs::widgets
