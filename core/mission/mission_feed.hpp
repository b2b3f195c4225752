#pragma once
// The order a mission hears its robot in. A primitive's report goes before the first sample at
// or after its time; reports newer than every sample go right after the newest one (a robot
// reports before the telemetry of the same moment arrives, or its telemetry stalls: a mission
// waiting for a final report must not wait for a sample that may not come). MissionRunner
// (irgs-sim, scenarios) and the GUI's mission activity both feed missions through it.

#include <span>
#include <vector>

#include "core/mission/mission.hpp"

namespace irgs {

// Calls on_report(report) and on_sample(sample) for `reports` (times on the samples' clock) and
// `samples` merged in time order; either returns false to stop there (the mission finished).
// `reports` is left empty: what was not delivered is not this mission's any more.
template <class OnReport, class OnSample>
void feedInTimeOrder(std::vector<motion::MotionReport>& reports,
                     std::span<const TelemetrySample> samples, OnReport&& on_report,
                     OnSample&& on_sample) {
  std::size_t next = 0;
  const auto deliverUpTo = [&](double time_s) {
    while (next < reports.size() && reports[next].time_s <= time_s)
      if (!on_report(reports[next++]))
        return false;
    return true;
  };
  bool going = true;
  for (const TelemetrySample& sample : samples) {
    going = deliverUpTo(sample.time_s) && on_sample(sample);
    if (!going)
      break;
  }
  while (going && next < reports.size())
    going = on_report(reports[next++]);
  reports.clear();
}

// Hands every request the mission has made since the last call to `apply`, in order.
template <class Apply>
void takeRequests(Mission& mission, Apply&& apply) {
  while (std::optional<MissionRequest> request = mission.takeRequest())
    apply(*request);
}

}  // namespace irgs
