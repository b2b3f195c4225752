#pragma once
// ARCOS server information packets (SIPs): the standard SIP sent every SipCycle (100 ms on a
// P3-DX) and the SYNC2 reply carrying the robot's name, class and subclass. Layout from the
// Pioneer 3 Operations Manual (Table "ARCOS standard SIP contents"); all integers little-endian:
//
//   type 0x3S (S = 2 stopped, 3 moving) | XPOS u16 (15 bits) | YPOS u16 (15 bits) | THPOS i16 |
//   L VEL i16 | R VEL i16 | BATTERY u8 (0.1 V) | STALL AND BUMPERS u16 | CONTROL i16 |
//   FLAGS u16 | COMPASS u8 | SONAR COUNT u8 | { NUMBER u8, RANGE u16 } x count |
//   GRIP_STATE u8 | ANPORT u8 | ANALOG u8 | DIGIN u8 | DIGOUT u8 | BATTERYX10 u16 |
//   CHARGESTATE u8 | ROTVEL i16 | FAULTFLAGS u16
//
// Values are in robot units: convert with the model's DistConvFactor, AngleConvFactor,
// VelConvFactor and RangeConvFactor (resources/robots/pioneer_*.json). Older firmware (P2OS,
// AmigoBot) ends the packet earlier; every field after the sonar readings is optional and a
// packet that ends there is accepted.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace irgs::comms::arcos {

inline constexpr std::size_t kMaxSonars = 32;  // sonar disc numbers 0-31

struct SonarRangeRaw {
  std::uint8_t index = 0;
  std::uint16_t range = 0;  // robot units (x RangeConvFactor = mm)
  friend bool operator==(const SonarRangeRaw&, const SonarRangeRaw&) = default;
};

struct StandardSip {
  std::uint8_t type = 0x32;
  std::uint16_t x_raw = 0;  // 15-bit wrapping counters (OdometryUnwrapper)
  std::uint16_t y_raw = 0;
  std::int16_t theta_raw = 0;  // AngleConvFactor units (2 pi / 4096 on ARCOS robots)
  std::int16_t left_velocity = 0;
  std::int16_t right_velocity = 0;
  std::uint8_t battery_decivolts = 0;
  std::uint16_t stall_and_bumpers = 0;  // bit 0 left stall, 1-7 rear bumpers, 8 right stall,
                                        // 9-15 front bumpers
  std::int16_t control = 0;
  std::uint16_t flags = 0;  // bit 0 motors enabled, 1-4 sonar arrays, 5 stop button, 6 e-stall
  std::uint8_t compass = 0;
  std::vector<SonarRangeRaw> sonars;  // the readings new in this cycle, at most kMaxSonars
  // Present when the packet carries them (ARCOS yes, P2OS/AmigoBot possibly not).
  std::optional<std::array<std::uint8_t, 5>> io;  // GRIP_STATE ANPORT ANALOG DIGIN DIGOUT
  std::optional<std::uint16_t> battery_x10;
  std::optional<std::uint8_t> charge_state;
  std::optional<std::int16_t> rotational_velocity;  // 0.1 deg/s
  std::optional<std::uint16_t> fault_flags;

  bool moving() const { return (type & 0x0F) == 3; }
  bool leftStalled() const { return (stall_and_bumpers & 0x0001) != 0; }
  bool rightStalled() const { return (stall_and_bumpers & 0x0100) != 0; }
  std::uint8_t rearBumpers() const {
    return static_cast<std::uint8_t>(stall_and_bumpers >> 1 & 0x7F);
  }
  std::uint8_t frontBumpers() const {
    return static_cast<std::uint8_t>(stall_and_bumpers >> 9 & 0x7F);
  }
  bool motorsEnabled() const { return (flags & 0x0001) != 0; }

  friend bool operator==(const StandardSip&, const StandardSip&) = default;
};

inline bool isStandardSipType(std::uint8_t type) {
  return (type & 0xF0) == 0x30;
}

struct SipParseResult {
  std::optional<StandardSip> sip;
  std::string error;  // set when sip is empty: which field ran past the end, or the bad value
};
// Parses a standard SIP payload (type byte first). Tolerant of short packets after the sonar
// readings and of trailing bytes it does not know; strict about everything before.
SipParseResult parseStandardSip(std::span<const std::uint8_t> payload);
// The payload of a standard SIP (the virtual Pioneer sends these). Optional fields are written
// up to the last one present (a missing earlier one is written as zero). Throws
// std::invalid_argument with more than kMaxSonars readings or a sonar index above 31.
std::vector<std::uint8_t> encodeStandardSip(const StandardSip& sip);

// The server's answer to SYNC2: payload 0x02 then three NUL-terminated strings.
struct RobotIdentity {
  std::string name;         // e.g. "MobileSim", or the robot's serial name
  std::string robot_class;  // e.g. "Pioneer"
  std::string subclass;     // e.g. "p3dx"
  friend bool operator==(const RobotIdentity&, const RobotIdentity&) = default;
};
std::optional<RobotIdentity> parseSync2Reply(std::span<const std::uint8_t> payload);
std::vector<std::uint8_t> encodeSync2Reply(const RobotIdentity& identity);

// Accumulates a 15-bit wrapping odometry counter (XPOS/YPOS) into an unbounded count. The first
// value sets the origin (returns 0); each later one adds the shortest signed step modulo 2^15,
// so travel of up to half the range (16 m at 1 mm/unit) between two SIPs is tracked.
class OdometryUnwrapper {
 public:
  std::int64_t update(std::uint16_t raw);
  void reset() {
    last_.reset();
    total_ = 0;
  }
  std::int64_t total() const { return total_; }

 private:
  std::optional<std::uint16_t> last_;
  std::int64_t total_ = 0;
};

}  // namespace irgs::comms::arcos
