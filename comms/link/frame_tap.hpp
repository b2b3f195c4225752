#pragma once
// A tap on a Link's byte stream: every chunk of bytes received from the transport (before the
// decoder sees it) and every encoded frame handed to the transport, with the steady-clock time
// it crossed. Session recording (app/recording) uses it; replay feeds the received chunks back
// through a ReplayTransport (comms/transport/replay_transport.hpp) so the decoder, the link
// session and LinkedRobot see exactly what they saw live.
//
// The tap runs on the link's io thread, inside the receive / transmit path of every link on
// that thread: it must only copy the bytes somewhere (a queue) and return. Exceptions are
// caught and counted like any link callback's.

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>

namespace irgs::comms {

enum class TapDirection : std::uint8_t {
  kReceived = 0,  // from the peer: one transport read, possibly several or partial frames
  kSent = 1,      // to the peer: one encoded frame the transport accepted
};

inline std::string_view toString(TapDirection direction) {
  return direction == TapDirection::kReceived ? "rx" : "tx";
}

// `bytes` is valid only during the call.
using FrameTap =
    std::function<void(TapDirection direction, std::chrono::steady_clock::time_point time,
                       std::span<const std::uint8_t> bytes)>;

}  // namespace irgs::comms
