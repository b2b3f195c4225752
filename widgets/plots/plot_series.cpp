#include "widgets/plots/plot_series.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs::widgets {

PlotSeries::PlotSeries(std::size_t capacity) : buffer_(capacity) {
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
  if (size_ < buffer_.size()) {
    buffer_[(head_ + size_) % buffer_.size()] = {time_s, value};
    ++size_;
  } else {
    buffer_[head_] = {time_s, value};
    head_ = (head_ + 1) % buffer_.size();
  }
  return true;
}

void PlotSeries::clear() {
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
  std::optional<PlotRange> out;
  for (std::size_t i = lowerBound(t0); i < size_ && at(i).time_s <= t1; ++i) {
    const double v = at(i).value;
    if (!out)
      out = PlotRange{v, v};
    out->min = std::min(out->min, v);
    out->max = std::max(out->max, v);
  }
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
    for (std::size_t i = begin; i < end; ++i) {
      const PlotSample& s = at(i);
      out.push_back({s.time_s, s.value, s.value, s.value, s.value});
    }
    return out;
  }
  out.reserve(static_cast<std::size_t>(columns));
  const double width_s = (t1 - t0) / columns;
  int current = -1;
  for (std::size_t i = begin; i < end; ++i) {
    const PlotSample& s = at(i);
    const int column = std::clamp(static_cast<int>((s.time_s - t0) / width_s), 0, columns - 1);
    if (column != current) {
      out.push_back({s.time_s, s.value, s.value, s.value, s.value});
      current = column;
      continue;
    }
    PlotColumn& c = out.back();
    c.min = std::min(c.min, s.value);
    c.max = std::max(c.max, s.value);
    c.last = s.value;
  }
  return out;
}

std::vector<PlotSample> PlotSeries::samples(double t0, double t1) const {
  std::vector<PlotSample> out;
  for (std::size_t i = lowerBound(t0); i < size_ && at(i).time_s <= t1; ++i)
    out.push_back(at(i));
  return out;
}

}  // namespace irgs::widgets
