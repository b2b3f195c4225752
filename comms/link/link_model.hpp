#pragma once
// A model of one direction of a slow, late, lossy serial link — a Bluetooth SPP module on a UART,
// a radio modem — for tests and for the irgs-linkem relay: bytes leave one at a time at the
// baud rate (10 bits a byte: 8N1), arrive a latency (plus uniform jitter per write) later in
// the order they were sent and no closer than a byte time (the far end's UART), are held while
// the link stalls (every stall_every_s for stall_s, delivered at the baud after), and each byte
// may be lost or have a bit flipped. Pure: the time
// is the caller's (a simulated clock or the wall clock), and the same seed and writes give the
// same deliveries.

#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace irgs::comms {

struct LinkModelConfig {
  double delay_s = 0.0;        // one-way latency
  double jitter_s = 0.0;       // plus uniform [0, jitter] per write (order kept)
  double baud = 0.0;           // 0: no rate limit
  double stall_every_s = 0.0;  // a stall of stall_s starts every this many seconds (0: none)
  double stall_s = 0.0;
  double stall_phase_s = 0.0;  // the first stall starts at stall_every_s + phase
  double loss = 0.0;           // probability per byte of being dropped
  double corruption = 0.0;     // probability per byte of one flipped bit
  std::uint64_t seed = 1;
};

// What is wrong with the config (negative or non-finite values, probabilities beyond [0, 1],
// a stall not shorter than its period), or nothing.
std::optional<std::string> linkModelConfigError(const LinkModelConfig& config);

struct LinkModelStats {
  std::uint64_t bytes_in = 0;
  std::uint64_t bytes_out = 0;
  std::uint64_t lost = 0;
  std::uint64_t corrupted = 0;
};

class LinkModel {
 public:
  // Throws std::invalid_argument for a bad config.
  explicit LinkModel(LinkModelConfig config = {});

  // Bytes entering the link at now_s (non-decreasing across calls).
  void send(std::span<const std::uint8_t> bytes, double now_s);
  // The bytes that have arrived by now_s, in order.
  std::vector<std::uint8_t> receive(double now_s);
  // When the next byte arrives (nothing queued: empty).
  std::optional<double> nextArrival_s() const;
  std::size_t queuedBytes() const { return queue_.size(); }
  const LinkModelStats& stats() const { return stats_; }
  const LinkModelConfig& config() const { return config_; }

 private:
  // The end of the stall that holds a delivery due at t, or t when none does.
  double afterStalls(double t) const;

  struct InFlight {
    double arrival_s;
    std::uint8_t byte;
  };
  LinkModelConfig config_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  std::deque<InFlight> queue_;
  double line_free_s_ = 0.0;     // when the sender's UART finishes the bytes before
  double last_arrival_s_ = 0.0;  // arrivals never overtake each other
  LinkModelStats stats_;
};

}  // namespace irgs::comms
