// The virtual Pioneer (ArcosFirmware) driven by a fake client on a fake clock: the handshake,
// driving, the PULSE watchdog, SETO/HEAD/VEL2, and 15-bit odometry wrap-around over > 32.8 m
// read back through the client-side converter.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/robot/arcos_firmware.hpp"
#include "comms/arcos/arcos_commands.hpp"
#include "comms/arcos/arcos_packet.hpp"
#include "comms/arcos/arcos_sip.hpp"
#include "comms/robot/arcos_telemetry.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"

namespace irgs::app {
namespace {

namespace arcos = comms::arcos;
using arcos::Command;

RobotProfile pioneer(const std::string& model) {
  auto loaded = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_" +
                                     model + ".json");
  if (!loaded.profile)
    throw std::runtime_error("cannot load pioneer_" + model);
  return *loaded.profile;
}

// A 10 m room around the origin, or nothing at all (open space for long drives).
WorldMap room(bool walls) {
  WorldMap map;
  if (walls) {
    Wall box;
    box.id = "box";
    box.points = {Vec2(-5, -5), Vec2(5, -5), Vec2(5, 5), Vec2(-5, 5)};
    box.closed = true;
    map.walls.push_back(box);
  }
  return map;
}

struct Client {
  explicit Client(const std::string& model = "p3dx", bool walls = true,
                  ArcosFirmwareConfig config = {})
      : fw(Simulator(room(walls), pioneer(model), idealSimConfig(SimConfig{})), config) {}

  void send(const std::vector<std::uint8_t>& packet) { fw.receiveBytes(packet, t); }
  void command(Command c) { send(arcos::commandPacket(c)); }
  void command(Command c, int arg) { send(arcos::commandPacket(c, arg)); }
  // Advances the fake clock in 10 ms steps, decoding everything the firmware writes.
  void run(double seconds, double pulse_period_s = 0.0) {
    const double end = t + seconds;
    double next_pulse = t + pulse_period_s;
    while (t < end - 1e-9) {
      t += 0.01;
      if (pulse_period_s > 0.0 && t >= next_pulse - 1e-6) {
        send(arcos::commandPacket(arcos::kPulse));
        next_pulse += pulse_period_s;
      }
      fw.advance(t);
      std::vector<std::uint8_t> out = fw.takeOutput();
      decoder.feed(out, packets);
    }
  }
  std::vector<arcos::StandardSip> takeSips() {
    std::vector<arcos::StandardSip> sips;
    for (const auto& p : packets) {
      if (arcos::isStandardSipType(p.type())) {
        auto parsed = arcos::parseStandardSip(p.payload());
        EXPECT_TRUE(parsed.sip.has_value()) << parsed.error;
        if (parsed.sip)
          sips.push_back(*parsed.sip);
      }
    }
    packets.clear();
    return sips;
  }
  void handshake() {
    send(arcos::commandPacket(arcos::kPulse));
    send(arcos::commandPacket(1));
    send(arcos::commandPacket(2));
    send(arcos::commandPacket(arcos::kOpen));
    fw.takeOutput();
    ASSERT_EQ(fw.state(), ArcosServerState::kOpen);
  }

  ArcosFirmware fw;
  double t = 0.0;
  arcos::PacketDecoder decoder;
  std::vector<arcos::Packet> packets;
};

TEST(ArcosFirmware, AnswersTheSyncHandshakeWithNameClassAndSubclass) {
  Client c;
  c.send(arcos::commandPacket(1));  // SYNC1 before SYNC0: ignored
  EXPECT_TRUE(c.fw.takeOutput().empty());
  c.send(arcos::commandPacket(arcos::kPulse));
  EXPECT_EQ(c.fw.takeOutput(), (std::vector<std::uint8_t>{0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00}));
  c.send(arcos::commandPacket(1));
  EXPECT_EQ(c.fw.takeOutput(), (std::vector<std::uint8_t>{0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01}));
  c.send(arcos::commandPacket(2));
  std::vector<std::uint8_t> out = c.fw.takeOutput();
  std::vector<arcos::Packet> packets;
  c.decoder.feed(out, packets);
  ASSERT_EQ(packets.size(), 1u);
  const auto identity = arcos::parseSync2Reply(packets[0].payload());
  ASSERT_TRUE(identity.has_value());
  EXPECT_EQ(*identity, (arcos::RobotIdentity{"irgs-robot", "Pioneer", "p3dx-sh"}));
  EXPECT_EQ(c.fw.state(), ArcosServerState::kSynced);

  c.run(0.5);
  EXPECT_TRUE(c.takeSips().empty()) << "no SIPs before OPEN";
  c.send(arcos::commandPacket(arcos::kOpen));
  c.run(1.0, 0.5);
  const auto sips = c.takeSips();
  EXPECT_GE(sips.size(), 9u);  // every 100 ms
  EXPECT_LE(sips.size(), 11u);
  EXPECT_EQ(sips.back().type, 0x32);  // stopped
  EXPECT_TRUE(sips.back().motorsEnabled());
}

TEST(ArcosFirmware, AmigoBotReportsItsOwnSubclassAndEightSonars) {
  Client c("amigo");
  c.handshake();
  c.run(2.0, 0.5);
  std::set<int> seen;
  for (const auto& sip : c.takeSips())
    for (const auto& r : sip.sonars)
      seen.insert(r.index);
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_EQ(*seen.rbegin(), 7);
}

TEST(ArcosFirmware, VelAndRvelDriveTheSimulatorAndSipsReportIt) {
  Client c;
  c.handshake();
  c.command(Command::kVel, 300);
  c.run(3.0, 0.5);
  const auto sips = c.takeSips();
  ASSERT_FALSE(sips.empty());
  EXPECT_EQ(sips.back().type, 0x33);  // moving
  EXPECT_NEAR(sips.back().left_velocity, 300, 2);
  EXPECT_NEAR(sips.back().right_velocity, 300, 2);
  // 0.3 m/s reached after 1 s at 0.3 m/s^2: 0.15 + 0.6 m in 3 s.
  EXPECT_NEAR(c.fw.reportedPose().x, 0.75, 0.03);
  EXPECT_NEAR(sips.back().x_raw, c.fw.reportedPose().x * 1000.0, 35.0);

  c.command(Command::kVel, 0);
  c.command(Command::kRVel, 30);
  c.run(2.0, 0.5);
  const auto turning = c.takeSips();
  EXPECT_NEAR(*turning.back().rotational_velocity, 300, 3);  // 0.1 deg/s units
  EXPECT_GT(c.fw.reportedPose().theta, degToRad(30.0));
}

TEST(ArcosFirmware, StopsWhenNoCommandOrPulseArrivesForTheWatchdogTime) {
  Client c;
  c.handshake();
  c.command(Command::kVel, 300);
  c.run(1.9);  // no PULSE
  EXPECT_GT(c.fw.simulator().trueVelocity().linear_mps, 0.25);
  EXPECT_EQ(c.fw.stats().watchdog_stops, 0u);
  c.run(0.2);
  EXPECT_EQ(c.fw.stats().watchdog_stops, 1u);
  EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0);
  c.run(1.0);
  EXPECT_EQ(c.fw.stats().watchdog_stops, 1u) << "trips once";
  EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0);
  // A new motion command moves it again.
  c.command(Command::kVel, 200);
  c.run(1.0, 0.5);
  EXPECT_GT(c.fw.simulator().trueVelocity().linear_mps, 0.15);
}

TEST(ArcosFirmware, WatchdogTimeIsConfigurable) {
  ArcosFirmwareConfig config;
  config.watchdog_s = 0.5;
  Client c("p3dx", true, config);
  c.handshake();
  c.command(Command::kVel, 300);
  c.run(0.45);
  EXPECT_EQ(c.fw.stats().watchdog_stops, 0u);
  c.run(0.1);
  EXPECT_EQ(c.fw.stats().watchdog_stops, 1u);
}

TEST(ArcosFirmware, StopEstopCloseAndDisableStopTheRobot) {
  for (int variant = 0; variant < 4; ++variant) {
    Client c;
    c.handshake();
    c.command(Command::kVel, 300);
    c.run(1.5, 0.5);
    ASSERT_GT(c.fw.simulator().trueVelocity().linear_mps, 0.25);
    if (variant == 0)
      c.command(Command::kStop);
    else if (variant == 1)
      c.command(Command::kEStop);
    else if (variant == 2)
      c.send(arcos::commandPacket(arcos::kClose));
    else
      c.command(Command::kEnable, 0);
    c.run(1.5, 0.5);
    EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0) << "variant " << variant;
  }
}

TEST(ArcosFirmware, DisabledMotorsIgnoreMotionCommandsUntilEnabled) {
  Client c;
  c.handshake();
  c.command(Command::kEnable, 0);
  c.command(Command::kVel, 300);
  c.run(1.0, 0.5);
  EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0);
  EXPECT_FALSE(c.takeSips().back().motorsEnabled());
  c.command(Command::kEnable, 1);
  c.command(Command::kVel, 300);
  c.run(1.0, 0.5);
  EXPECT_GT(c.fw.simulator().trueVelocity().linear_mps, 0.2);
}

TEST(ArcosFirmware, HeadTurnsToAnAbsoluteHeadingAndSetoResetsTheOrigin) {
  Client c;
  c.handshake();
  c.command(Command::kHead, 90);
  c.run(4.0, 0.5);
  EXPECT_NEAR(c.fw.reportedPose().theta, degToRad(90.0), degToRad(1.0));
  EXPECT_NEAR(c.takeSips().back().theta_raw, std::lround(degToRad(90.0) / 0.001534), 12);
  c.command(Command::kDHead, -45);
  c.run(3.0, 0.5);
  EXPECT_NEAR(c.fw.reportedPose().theta, degToRad(45.0), degToRad(1.0));
  c.command(Command::kSetO);
  c.run(0.2, 0.5);
  EXPECT_NEAR(c.fw.reportedPose().theta, 0.0, 1e-9);
  const auto sips = c.takeSips();
  EXPECT_EQ(sips.back().x_raw, 0);
  EXPECT_EQ(sips.back().theta_raw, 0);
}

TEST(ArcosFirmware, Vel2SetsTheWheelSpeedsInDivisorUnits) {
  Client c;
  c.handshake();
  c.command(Command::kVel2, arcos::vel2Argument(10, 10));  // 200 mm/s each
  c.run(2.0, 0.5);
  EXPECT_NEAR(c.fw.simulator().trueVelocity().linear_mps, 0.2, 0.005);
  // Spin in place, CCW: the negative left wheel makes the argument a negative int, as in ARIA.
  c.command(Command::kVel2, arcos::vel2Argument(-5, 5));
  c.run(2.0, 0.5);
  EXPECT_NEAR(c.fw.simulator().trueVelocity().linear_mps, 0.0, 0.005);
  EXPECT_GT(c.fw.simulator().trueVelocity().angular_radps, 0.3);
}

TEST(ArcosFirmware, MoveTravelsARelativeDistance) {
  Client c;
  c.handshake();
  c.command(Command::kMove, 500);
  c.run(5.0, 0.5);
  EXPECT_NEAR(c.fw.reportedPose().x, 0.5, 0.01);
  EXPECT_NEAR(c.fw.simulator().trueVelocity().linear_mps, 0.0, 1e-3);
}

TEST(ArcosFirmware, SonarReadingsArriveByDiscNumberAndSonarOffSilencesThem) {
  Client c;
  c.handshake();
  c.run(1.0, 0.5);
  int readings = 0;
  for (const auto& sip : c.takeSips()) {
    for (const auto& r : sip.sonars) {
      ++readings;
      EXPECT_LT(r.index, 16);
      EXPECT_GT(r.range, 100);  // the room's walls are 4.4-7 m away; at most 5000 (no echo)
      EXPECT_LE(r.range, 5000);
    }
  }
  EXPECT_GE(readings, 30);  // 16 discs at 3.125 Hz for 1 s: ~50
  c.command(Command::kSonar, 0);
  c.run(1.0, 0.5);
  for (const auto& sip : c.takeSips()) {
    EXPECT_TRUE(sip.sonars.empty());
    EXPECT_EQ(sip.flags & 0x1E, 0);
  }
}

TEST(ArcosFirmware, GarbageAndBadCommandsAreCountedNotFatal) {
  Client c;
  c.handshake();
  c.send({0xFA, 0xFB, 0x05, 0x0B, 0x3B, 0xC8, 0x00, 0x00});   // bad checksum
  c.send({0xFA, 0xFB, 0x04, 0x0B, 0x99, 0x0B, 0x99 ^ 0x00});  // bad argument type
  c.send({0x00, 0x13, 0xFA, 0x42});
  std::vector<std::uint8_t> noise(500);
  for (std::size_t i = 0; i < noise.size(); ++i)
    noise[i] = static_cast<std::uint8_t>(i * 37 + 11);
  c.send(noise);
  c.run(0.5, 0.2);
  EXPECT_GE(c.fw.stats().packets.bad_checksum + c.fw.stats().bad_commands, 1u);
  EXPECT_EQ(c.fw.state(), ArcosServerState::kOpen);
  EXPECT_FALSE(c.takeSips().empty());
}

TEST(ArcosFirmware, OdometryWrapsAt15BitsAndTheClientUnwrapsItOverFortyMetres) {
  Client c("p3dx", /*walls=*/false);
  comms::ArcosTelemetryConverter converter(
      c.fw.simulator().profile(), comms::arcosParamsFromProfile(c.fw.simulator().profile()).params);
  c.handshake();
  c.command(Command::kVel, 2000);
  int wraps = 0;
  std::uint16_t last_raw = 0;
  TelemetrySample last;
  while (c.fw.reportedPose().x < 40.0) {
    c.run(0.5, 0.5);
    for (const auto& sip : c.takeSips()) {
      if (sip.x_raw < last_raw)
        ++wraps;
      last_raw = sip.x_raw;
      last = converter.convert(sip, c.t);
    }
    ASSERT_LT(c.t, 60.0);
  }
  EXPECT_EQ(wraps, 1);  // 32.768 m
  EXPECT_GT(last.odometry_pose.x, 32.8);
  EXPECT_NEAR(last.odometry_pose.x, c.fw.reportedPose().x, 0.25);  // SIP is up to 100 ms old
  EXPECT_NEAR(last.odometry_pose.y, 0.0, 0.002);
}

// Strict mode: what the Pioneer manuals say a real robot does with a client that breaks the
// rules (app/robot/arcos_firmware.hpp, docs/pioneer.md "Strict mode").
ArcosFirmwareConfig strict(std::optional<std::uint32_t> link_baud = std::nullopt) {
  ArcosFirmwareConfig config;
  config.strict = true;
  config.link_baud = link_baud;
  return config;
}

std::vector<std::uint8_t> concat(std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(ArcosFirmware, StrictModeLosesACommandCloserThanFiveMillisecondsToThePrevious) {
  Client c("p3dx", true, strict());
  c.handshake();
  c.t += 0.02;
  // VEL and RVEL written back to back (the client before issue 24): over TCP they arrive
  // together, and the command processor takes only the first.
  c.send(
      concat(arcos::commandPacket(Command::kVel, 200), arcos::commandPacket(Command::kRVel, 20)));
  c.run(1.0, 0.5);
  EXPECT_EQ(c.fw.stats().too_soon, 1u);
  EXPECT_NEAR(c.fw.simulator().trueVelocity().linear_mps, 0.2, 0.01);
  EXPECT_EQ(c.fw.simulator().trueVelocity().angular_radps, 0.0) << "the RVEL was lost";
  // 3 ms later is still too soon; 5 ms later is taken.
  c.t += 0.01;
  c.command(Command::kRVel, 20);
  c.t += 0.003;
  c.command(Command::kRVel, 30);
  c.t += 0.005;
  c.command(Command::kSetO);
  EXPECT_EQ(c.fw.stats().too_soon, 2u);
  EXPECT_EQ(c.fw.stats().commands, 2u + 3u);  // VEL, 2 PULSEs, RVEL 20, SETO
}

TEST(ArcosFirmware, StrictModeOnASerialLineSpreadsAReadAtTheBytesTime) {
  // At 9600 baud a 9-byte packet takes 9.4 ms on the wire: the same two packets in one read
  // arrived that far apart, and both are taken.
  Client c("p3dx", true, strict(9600));
  c.handshake();
  c.t += 0.02;
  c.send(
      concat(arcos::commandPacket(Command::kVel, 200), arcos::commandPacket(Command::kRVel, 20)));
  EXPECT_EQ(c.fw.stats().too_soon, 0u);
  EXPECT_EQ(c.fw.stats().commands, 2u);
  // At 115200 baud the second follows 0.8 ms after the first: lost.
  Client fast("p3dx", true, strict(115200));
  fast.handshake();
  fast.t += 0.02;
  fast.send(
      concat(arcos::commandPacket(Command::kVel, 200), arcos::commandPacket(Command::kRVel, 20)));
  EXPECT_EQ(fast.fw.stats().too_soon, 1u);
}

TEST(ArcosFirmware, StrictModeBlamesTheClientOnlyForWhatCertainlyCameTooSoon) {
  const std::vector<std::uint8_t> pair =
      concat(arcos::commandPacket(Command::kVel, 200), arcos::commandPacket(Command::kRVel, 20));
  // Polled every millisecond: the pair came within 1 ms, so the RVEL was too soon.
  Client prompt("p3dx", true, strict(115200));
  prompt.handshake();
  prompt.t += 0.02;
  prompt.fw.receiveBytes(pair, prompt.t, prompt.t - 0.001);
  EXPECT_EQ(prompt.fw.stats().too_soon, 1u);
  // Read 25 ms after the previous poll (the emulator was not scheduled): the two may have come
  // 12 ms apart, as a client that spaces its commands sends them. Both are taken.
  Client late("p3dx", true, strict(115200));
  late.handshake();
  late.t += 0.02;
  late.fw.receiveBytes(pair, late.t, late.t - 0.025);
  EXPECT_EQ(late.fw.stats().too_soon, 0u);
  EXPECT_EQ(late.fw.stats().commands, 2u);
  // Four in 8 ms are at most 2 ms apart wherever they fell: after each one it takes, the
  // command processor loses what comes within 5 ms (the second and the third).
  Client crowded("p3dx", true, strict(115200));
  crowded.handshake();
  crowded.t += 0.02;
  const std::vector<std::uint8_t> four = concat(concat(pair, arcos::commandPacket(Command::kSetO)),
                                                arcos::commandPacket(arcos::kPulse));
  crowded.fw.receiveBytes(four, crowded.t, crowded.t - 0.008);
  EXPECT_EQ(crowded.fw.stats().too_soon, 2u);
}

TEST(ArcosFirmware, StrictModeOnASerialLineKnowsTwoReadsCannotBeCloserThanTheWire) {
  // A bridge (or a late read) hands over in two reads 0.2 ms apart what a 9600-baud line
  // delivered 9.4 ms apart: both taken. At 115200 baud the line itself brings them too close.
  for (const auto& [baud, lost] : {std::pair{9600u, 0u}, std::pair{115200u, 1u}}) {
    Client c("p3dx", true, strict(baud));
    c.handshake();
    c.t += 0.02;
    c.command(Command::kVel, 200);
    c.t += 0.0002;
    c.command(Command::kRVel, 20);
    EXPECT_EQ(c.fw.stats().too_soon, lost) << baud;
  }
}

TEST(ArcosFirmware, StrictModeIgnoresAPacketWithMoreThanOneCommand) {
  Client c("p3dx", true, strict());
  c.handshake();
  c.t += 0.02;
  // VEL 200 and RVEL 20 in one packet: not a command ARCOS knows.
  c.send(arcos::framePacket(concat(arcos::commandPayload(Command::kVel, 200),
                                   arcos::commandPayload(Command::kRVel, 20))));
  // A count byte above the manuals' 249 (a string argument of 250 bytes).
  c.t += 0.02;
  std::vector<std::uint8_t> long_payload{3, arcos::kArgString, 249};
  long_payload.resize(3 + 249, 'x');
  c.send(arcos::framePacket(long_payload));
  EXPECT_EQ(c.fw.stats().bad_commands, 2u);
  EXPECT_EQ(c.fw.stats().commands, 0u);
  c.run(0.5);
  EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0);
}

TEST(ArcosFirmware, StrictWatchdogHaltsAndTheNextCommandResumesTheSetPoints) {
  Client c("p3dx", true, strict());
  c.handshake();
  c.t += 0.02;
  c.command(Command::kVel, 300);
  c.run(2.5);  // silence: the watchdog halts the motors after 2 s
  EXPECT_EQ(c.fw.stats().watchdog_stops, 1u);
  EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0);
  c.run(1.0);
  EXPECT_EQ(c.fw.simulator().trueVelocity().linear_mps, 0.0) << "halted while silent";
  // "it will revive upon receipt of a client command and automatically accelerate to the
  // last-specified speed": a PULSE is enough.
  c.send(arcos::commandPacket(arcos::kPulse));
  c.run(1.5, 0.5);
  EXPECT_NEAR(c.fw.simulator().trueVelocity().linear_mps, 0.3, 0.01);
  EXPECT_EQ(c.fw.stats().watchdog_stops, 1u);
}

TEST(ArcosFirmware, CountsCommandPacketsPerSecondAsTheyArrive) {
  Client c;  // both modes count
  c.handshake();
  for (int i = 0; i < 30; ++i) {  // 30 packets 20 ms apart: 0.6 s of a 50/s flood
    c.t += 0.02;
    c.command(Command::kRVel, i);
  }
  c.run(2.0, 0.5);  // then PULSE at 2/s
  EXPECT_EQ(c.fw.stats().peak_commands_per_s, 30u);
  EXPECT_EQ(c.fw.commandRate().count(), 30u + 4u);
}

}  // namespace
}  // namespace irgs::app
