#pragma once
// Decoded MAVLink messages of a linked robot for whoever shows "any field of any message" (the
// GUI's plots), without flooding it: pure (no Asio, no threads, no clock; the owner passes the
// arrival time), run by LinkedRobot on the io thread.
//
// Each frame of a message with a generated field table (comms/mavlink/field_info.hpp) becomes a
// MessageSample: the message's table, its instance (DISTANCE_SENSOR's sensor id: one stream per
// sensor), its robot-clock time and every numeric value. Thinning is per stream (message id +
// instance) by a token bucket on the arrival time: on average at most max_rate_hz samples per
// second pass, bursts of up to `burst` (several frames in one transport read) pass whole. So a
// 20 Hz stream at max_rate_hz 25 passes entirely and a replay at x16 or a chatty robot is
// thinned to the rate. Samples wait in a bounded queue until take(); the oldest are dropped.
//
// Time: a message's own time stamp (time_boot_ms or time_usec, the robot's boot clock) when it
// has one, else the newest time stamp seen (HEARTBEAT, SYS_STATUS, ... have none: they sit at
// the robot time they arrived at). Untimed frames before the first time stamp wait for it and
// take it (the newest kMaxUntimed of them). A
// time stamp more than kRestartJump_s older than the newest starts the clock over (the robot
// rebooted); reset() forgets it (link re-established).

#include <cstdint>
#include <deque>
#include <optional>
#include <unordered_map>
#include <vector>

#include "comms/mavlink/field_info.hpp"
#include "comms/mavlink/frame.hpp"

namespace irgs::comms {

struct MessageSamplerConfig {
  double max_rate_hz = 0.0;  // per stream, on average; 0 = off (nothing is sampled)
  double burst = 8.0;        // samples a stream may send at once after a quiet spell
  std::size_t max_pending = 4096;
};

struct MessageSample {
  const mavlink::MessageFields* message = nullptr;  // name and table (static storage)
  std::optional<std::uint32_t> instance;            // the instance field's value, if any
  double robot_time_s = 0.0;                        // robot boot clock, see above
  std::vector<double> values;                       // one per message->fields entry
};

struct MessageSamplerCounters {
  std::uint64_t kept = 0;      // queued for take()
  std::uint64_t thinned = 0;   // over the stream's rate
  std::uint64_t dropped = 0;   // queued but pushed out before take()
  std::uint64_t unknown = 0;   // no field table for the message id
  std::uint64_t untimed = 0;   // arrived before any time stamp (held for the first one)
  std::uint64_t restarts = 0;  // robot clock jumped back
};

class MessageSampler {
 public:
  static constexpr double kRestartJump_s = 1.0;
  static constexpr std::size_t kMaxUntimed = 64;

  // Throws std::invalid_argument for a negative or non-finite rate, or a burst < 1 when on.
  explicit MessageSampler(MessageSamplerConfig config = {});

  bool enabled() const { return config_.max_rate_hz > 0.0; }
  // One frame from the robot; `now_s` is its arrival time (monotonic seconds).
  void onFrame(const mavlink::Frame& frame, double now_s);
  // Forgets the robot clock (the robot may have restarted); queued samples stay.
  void reset();
  // Queued samples, oldest first.
  std::vector<MessageSample> take();

  const MessageSamplerCounters& counters() const { return counters_; }
  const MessageSamplerConfig& config() const { return config_; }

 private:
  struct Bucket {
    double tokens = 0.0;
    double last_s = 0.0;
  };
  bool admit(std::uint64_t stream, double now_s);
  void push(MessageSample sample);

  MessageSamplerConfig config_;
  std::optional<double> newest_time_s_;
  std::unordered_map<std::uint64_t, Bucket> buckets_;
  std::deque<MessageSample> pending_;
  std::deque<MessageSample> untimed_;  // waiting for the first time stamp
  MessageSamplerCounters counters_;
};

}  // namespace irgs::comms
