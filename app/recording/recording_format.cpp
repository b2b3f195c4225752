#include "app/recording/recording_format.hpp"

#include <algorithm>

namespace irgs::recording {

double Recording::duration_s() const {
  double t = 0.0;
  if (!frames.empty())
    t = std::max(t, frames.back().t_s);
  if (!events.empty())
    t = std::max(t, events.back().t_s);
  if (!truth.empty())
    t = std::max(t, truth.back().t_s);
  if (!commands.empty())
    t = std::max(t, commands.back().t_s);
  return t;
}

std::size_t Recording::receivedFrameCount() const {
  return static_cast<std::size_t>(std::count_if(frames.begin(), frames.end(),
                                                [](const RecordedFrame& f) { return f.dir == 0; }));
}

}  // namespace irgs::recording
