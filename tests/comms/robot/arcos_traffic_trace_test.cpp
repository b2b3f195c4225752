// The client's ARCOS traffic, byte for byte (issue 24: "a test with a literal byte trace shows
// the client's steady-state traffic"). The pure pieces ArcosRobot runs on its io thread, on a
// fake clock: ArcosClientSession (handshake, scheduler) ticked every 20 ms as ArcosRobot ticks
// it, a robot answering the handshake and sending a SIP every 100 ms, and a host behaviour that
// calls drive() every 2 ms with the command of the last SIP (as map building's wall following
// does), then stops. Before issue 24 this produced a VEL + RVEL pair per call: ~1000 packets/s.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "comms/arcos/arcos_commands.hpp"
#include "comms/arcos/arcos_session.hpp"
#include "comms/arcos/arcos_sip.hpp"
#include "comms/robot/arcos_robot.hpp"
#include "core/robot/robot_profile_file.hpp"

namespace irgs::comms {
namespace {

namespace arc = arcos;

struct Line {
  int ms;             // when it was written, ms on the client's clock
  std::string bytes;  // the packet as written, hex
  friend bool operator==(const Line&, const Line&) = default;
};
void PrintTo(const Line& l, std::ostream* os) {
  *os << l.ms << " ms: " << l.bytes;
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
  std::string out;
  char b[4];
  for (std::uint8_t v : bytes) {
    std::snprintf(b, sizeof b, out.empty() ? "%02x" : " %02x", v);
    out += b;
  }
  return out;
}

arc::Packet packetOf(const std::vector<std::uint8_t>& payload) {
  arc::Packet p;
  std::copy(payload.begin(), payload.end(), p.bytes.begin());
  p.size = payload.size();
  return p;
}

MotionLimits p3dxLimits() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_p3dx.json");
  if (!loaded.profile)
    throw std::runtime_error("cannot load pioneer_p3dx.json");
  return loaded.profile->limits;
}

// The host behaviour's answer to the SIP of time t: 0.3 m/s along the wall, a turn rate that
// changes with each SIP until 0.6 s, stop at 1.5 s.
VelocityCommand behaviourCommand(double t) {
  if (t < 0.3)
    return {0.3, degToRad(10.0)};
  if (t < 0.4)
    return {0.3, degToRad(12.0)};
  if (t < 0.5)
    return {0.3, degToRad(12.4)};  // 12 deg/s on the wire: no change
  if (t < 0.6)
    return {0.3, degToRad(-5.0)};
  return {0.3, degToRad(-4.0)};
}

TEST(ArcosTrafficTrace, MapBuildingSteadyStateIsChangesAndKeepAlivesOnly) {
  const MotionLimits limits = p3dxLimits();
  arc::ArcosClientSession session;
  std::vector<Line> trace;
  const auto collect = [&](int ms) {
    for (const auto& packet : session.takeOutgoing())
      trace.push_back({ms, hex(packet)});
  };
  bool stopped = false;
  for (int ms = 0; ms <= 2600; ++ms) {
    const double t = ms / 1000.0;
    // The robot: SYNC echoes 10 ms after each SYNC, the SYNC2 reply, then a SIP every 100 ms.
    if (ms == 0)
      session.start(t);
    else if (ms == 10)
      session.onPacket(packetOf({0}), t);
    else if (ms == 20)
      session.onPacket(packetOf({1}), t);
    else if (ms == 30)
      session.onPacket(packetOf(arc::encodeSync2Reply({"irgs-robot", "Pioneer", "p3dx-sh"})), t);
    else if (ms >= 130 && ms % 100 == 30)
      session.onPacket(packetOf(arc::encodeStandardSip({})), t);
    // The behaviour: drive() every 2 ms from 200 ms (ArcosRobot::drive: want + pump), then stop.
    if (ms >= 200 && ms < 1500 && ms % 2 == 0) {
      const ArcosVelocityArguments a = arcosVelocityArguments(behaviourCommand(t), limits);
      session.commands().want({arc::Command::kVel, a.vel_mmps});
      session.commands().want({arc::Command::kRVel, a.rvel_degps});
      session.pump(t);
    }
    if (ms >= 1500 && !stopped) {
      session.sendUrgent(arc::Command::kStop);
      session.pump(t);
      stopped = true;
    }
    if (ms % 20 == 0)
      session.tick(t);  // ArcosRobot's 20 ms tick
    collect(ms);
  }
  // Hand-checked: the bucket holds 2 packets and refills one per 110 ms; packets are >= 20 ms
  // apart; the newest wanted value goes when a token is there.
  const std::vector<Line> expected{
      {0, "fa fb 03 00 00 00"},              // SYNC0
      {10, "fa fb 03 01 00 01"},             // SYNC1, on SYNC0's echo
      {20, "fa fb 03 02 00 02"},             // SYNC2
      {30, "fa fb 03 01 00 01"},             // OPEN, on the SYNC2 reply (bucket 2 -> 1)
      {60, "fa fb 06 04 3b 01 00 05 3b"},    // ENABLE 1 (tick after the 20 ms gap)
      {140, "fa fb 06 1c 3b 01 00 1d 3b"},   // SONAR 1 (the next token, 110 ms later)
      {250, "fa fb 06 0b 3b 2c 01 37 3c"},   // VEL 300: wanted 25 times since 200 ms, sent once
      {360, "fa fb 06 15 3b 0c 00 21 3b"},   // RVEL 12: RVEL 10 (200-300 ms) never went
      {500, "fa fb 06 15 1b 05 00 1a 1b"},   // RVEL -5 (12.4 deg/s was RVEL 12 again: nothing)
      {600, "fa fb 06 15 1b 04 00 19 1b"},   // RVEL -4
      {1100, "fa fb 06 0b 3b 2c 01 37 3c"},  // keep-alive after 0.5 s: VEL 300 re-sent
      {1500, "fa fb 03 1d 00 1d"},           // STOP, at once
      {2000, "fa fb 06 0b 3b 00 00 0b 3b"},  // keep-alive: VEL 0 (the STOP's set point)
      {2500, "fa fb 06 15 3b 00 00 15 3b"},  // keep-alive: RVEL 0
  };
  EXPECT_EQ(trace, expected);
  // 650 drive() calls from 200 ms to 1.5 s: 1300 packets before issue 24, 5 now.
}

}  // namespace
}  // namespace irgs::comms
