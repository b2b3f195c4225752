#pragma once
// The data behind one plotted field: a fixed-capacity ring buffer of (time, value) samples in
// time order, and the min/max decimation a plot draws from. Plain C++ (no Qt) so the buffer and
// the decimation are unit-tested and benchmarked without a GUI.
//
// Drawing a 10-minute window of a 50 Hz field means 30 000 samples for a plot a few hundred
// pixels wide: decimate() reduces the samples of a time window to one (min, max) pair per pixel
// column, which draws as the same picture (every extreme is kept) in a bounded number of lines.

#include <cstddef>
#include <optional>
#include <vector>

namespace irgs::widgets {

struct PlotSample {
  double time_s = 0.0;
  double value = 0.0;
};

// One pixel column of a decimated window: the extremes of the samples that fall in it, the
// first and last sample (so consecutive columns join where the signal really went).
struct PlotColumn {
  double time_s = 0.0;  // time of the column's first sample
  double min = 0.0;
  double max = 0.0;
  double first = 0.0;
  double last = 0.0;
};

struct PlotRange {
  double min = 0.0;
  double max = 0.0;
};

class PlotSeries {
 public:
  // 50 Hz for a little over 20 minutes.
  static constexpr std::size_t kDefaultCapacity = 65536;

  explicit PlotSeries(std::size_t capacity = kDefaultCapacity);

  // Appends a sample. Non-finite values and samples older than the newest are dropped (returns
  // false); a sample more than kRestartGap_s older than the newest clears the buffer first (the
  // session restarted its clock) and is kept. When full, the oldest sample is overwritten.
  static constexpr double kRestartGap_s = 1.0;
  bool append(double time_s, double value);
  void clear();

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  // i-th sample, oldest first (i < size()).
  const PlotSample& at(std::size_t i) const { return buffer_[(head_ + i) % buffer_.size()]; }
  const PlotSample& newest() const { return at(size_ - 1); }
  const PlotSample& oldest() const { return at(0); }

  // Index of the first sample with time >= t (size() when none).
  std::size_t lowerBound(double time_s) const;
  // Extremes of the samples in [t0, t1]; nullopt when none falls inside.
  std::optional<PlotRange> range(double t0, double t1) const;
  // The samples in [t0, t1] reduced to at most `columns` columns of equal duration. Windows
  // with no more samples than columns come back one column per sample (min = max = value).
  std::vector<PlotColumn> decimate(double t0, double t1, int columns) const;
  // The samples in [t0, t1], oldest first (exports).
  std::vector<PlotSample> samples(double t0, double t1) const;

  // Calls f(sample) for the samples with logical indices [begin, end), oldest first, walking
  // the ring's (at most two) contiguous spans: no index arithmetic per sample.
  template <class F>
  void forEach(std::size_t begin, std::size_t end, F&& f) const {
    end = end < size_ ? end : size_;
    if (begin >= end)
      return;
    const std::size_t cap = buffer_.size();
    std::size_t physical = (head_ + begin) % cap;
    std::size_t left = end - begin;
    while (left > 0) {
      const std::size_t run = left < cap - physical ? left : cap - physical;
      const PlotSample* p = buffer_.data() + physical;
      for (std::size_t i = 0; i < run; ++i)
        f(p[i]);
      left -= run;
      physical = 0;
    }
  }

 private:
  // Grows with the samples up to capacity_ (a field that stays short costs little), then is a
  // ring: while not full, buffer_.size() == size_ and head_ == 0.
  std::vector<PlotSample> buffer_;
  std::size_t capacity_;
  std::size_t head_ = 0;  // physical index of the oldest sample
  std::size_t size_ = 0;
};

}  // namespace irgs::widgets
