#pragma once
// ARCOS/P2OS packet framing, as the Pioneer 3 Operations Manual ("ARCOS client-server
// communication packet protocol") and ARIA's ArBasePacket describe it:
//
//   0xFA 0xFB | count | payload (count - 2 bytes) | checksum (2 bytes, high byte first)
//
// `count` is the number of payload bytes plus the two checksum bytes. The checksum adds the
// payload as big-endian 16-bit words (byte i is the high byte, byte i+1 the low byte) modulo
// 2^16; with an odd number of bytes the last one is XORed into the sum. Multi-byte arguments
// INSIDE the payload are little-endian (arcos_commands.hpp, arcos_sip.hpp); only the checksum
// is big-endian.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace irgs::comms::arcos {

inline constexpr std::uint8_t kHeader0 = 0xFA;
inline constexpr std::uint8_t kHeader1 = 0xFB;
// The count byte can announce up to 255 bytes, i.e. 253 payload bytes. ARCOS itself never sends
// more than 200 (its packets are bounded by the SIP layout) but we accept what the byte allows.
inline constexpr std::size_t kMaxPayload = 253;
inline constexpr std::size_t kOverhead = 5;  // header (2) + count (1) + checksum (2)

std::uint16_t checksum(std::span<const std::uint8_t> payload);

// Frames a payload into a complete packet. Throws std::invalid_argument when the payload is
// empty or longer than kMaxPayload.
std::vector<std::uint8_t> framePacket(std::span<const std::uint8_t> payload);

struct PacketCounters {
  std::uint64_t packets = 0;        // delivered
  std::uint64_t bad_checksum = 0;   // complete candidate whose checksum did not match
  std::uint64_t bad_count = 0;      // count byte below 3 (no room for a type byte and checksum)
  std::uint64_t garbage_bytes = 0;  // bytes not part of any delivered packet

  PacketCounters& operator+=(const PacketCounters& other);
  friend bool operator==(const PacketCounters&, const PacketCounters&) = default;
};

// One checked packet: the payload without header, count and checksum. payload[0] is the packet
// type (SIP type, or the command number for client commands).
struct Packet {
  std::array<std::uint8_t, kMaxPayload> bytes{};
  std::size_t size = 0;
  std::span<const std::uint8_t> payload() const { return {bytes.data(), size}; }
  std::uint8_t type() const { return bytes[0]; }
};

// Turns a byte stream into checked packets. feed() takes any slice of the stream; bytes go into
// a fixed buffer (no allocation per byte). After a failed candidate only its first header byte is
// dropped and the search resumes right after it, so a packet starting inside garbage is found.
class PacketDecoder {
 public:
  PacketDecoder() = default;
  // Appends the completed packets to `out` (the caller clears and reuses it).
  PacketCounters feed(std::span<const std::uint8_t> bytes, std::vector<Packet>& out);
  const PacketCounters& totals() const { return totals_; }
  std::size_t bufferedBytes() const { return end_ - begin_; }
  void reset();

 private:
  void parse(std::vector<Packet>& out, PacketCounters& counters);

  static constexpr std::size_t kBufferSize = 2 * (kMaxPayload + kOverhead);
  std::array<std::uint8_t, kBufferSize> buffer_{};
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  PacketCounters totals_;
};

}  // namespace irgs::comms::arcos
