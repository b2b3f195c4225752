#pragma once
// Helpers for link tests: frames built through the real encoder/decoder, and messages picked
// out of a session's output.

#include "comms/link/link_session.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <variant>
#include <vector>

namespace irgs::comms::testing {

inline constexpr std::uint8_t kRobotSystem = 1;
inline constexpr std::uint8_t kRobotComponent = 1;

// The frame a receiver decodes when `system`/`component` sends `message`.
template <class M>
mavlink::Frame frameOf(const M& message, std::uint8_t system = kRobotSystem,
                       std::uint8_t component = kRobotComponent) {
  mavlink::FrameEncoder encoder(system, component);
  const auto encoded = encoder.encode(message);
  mavlink::FrameDecoder decoder;
  std::vector<mavlink::Frame> frames;
  decoder.feed(encoded.view(), frames);
  if (frames.size() != 1)
    throw std::logic_error("frameOf: encoding did not decode to one frame");
  return frames.front();
}

inline mavlink::Heartbeat robotHeartbeat() {
  mavlink::Heartbeat hb;
  hb.type = static_cast<std::uint8_t>(mavlink::MavType::kGroundRover);
  hb.autopilot = static_cast<std::uint8_t>(mavlink::MavAutopilot::kGeneric);
  hb.system_status = static_cast<std::uint8_t>(mavlink::MavState::kStandby);
  return hb;
}

template <class M>
std::vector<M> messagesOf(const SessionOutput& out) {
  std::vector<M> found;
  for (const auto& m : out.messages)
    if (const auto* typed = std::get_if<M>(&m))
      found.push_back(*typed);
  return found;
}

inline std::vector<LinkEvent> eventsOf(const SessionOutput& out, LinkEventKind kind) {
  std::vector<LinkEvent> found;
  for (const auto& e : out.events)
    if (e.kind == kind)
      found.push_back(e);
  return found;
}

}  // namespace irgs::comms::testing
