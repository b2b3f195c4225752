#pragma once
// What an optical floor (mouse) sensor of paper 004 reports over one sampling interval: the
// displacement of the floor under it as (x, y) counts in its own axes. A value type shared by
// the sensor model (core/estimation/mouse_sensor.hpp), the simulator and TelemetrySample.

#include <cstdint>

namespace irgs {

enum class MouseStatus {
  kTracking,   // counts are valid
  kSaturated,  // faster than the sensor's maximum speed: counts are clipped (under-reported)
  kLifted,     // floor gap above the sensor's lift-off height: no counts
};

const char* toString(MouseStatus status);

// Counts accumulated over one sampling interval, in the sensor's axes.
struct MouseCounts {
  std::int64_t dx = 0;
  std::int64_t dy = 0;
  MouseStatus status = MouseStatus::kTracking;
};

// The two sensors of a Type (2,0) robot with mouse odometry (paper 004, Fig. 3).
struct MouseReading {
  MouseCounts right;
  MouseCounts left;
};

}  // namespace irgs
