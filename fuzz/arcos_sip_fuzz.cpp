// libFuzzer harness for the ARCOS packet decoder, the standard-SIP parser and the client session.
// The first input byte chooses the chunking; the rest is the byte stream from the "robot".
// Invariants: no crash or sanitizer report; every byte accounted for (garbage, delivered packet
// or buffered); every delivered packet has a valid checksum; a SIP that parses re-encodes to a
// prefix of its payload (the parser never invents fields) and parses again to the same value.
//
//   build/fuzz/irgs_fuzz_arcos_sip -max_total_time=60 fuzz/corpus/arcos_sip

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "comms/arcos/arcos_packet.hpp"
#include "comms/arcos/arcos_session.hpp"
#include "comms/arcos/arcos_sip.hpp"
#include "fuzz/fuzz_check.hpp"

namespace arcos = irgs::comms::arcos;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::size_t chunk = 1 + (data[0] & 0x3F);
  const std::span<const std::uint8_t> stream(data + 1, size - 1);

  // The parser on the raw input, as if it were one payload.
  const auto direct = arcos::parseStandardSip(stream);
  IRGS_FUZZ_CHECK(direct.sip.has_value() != !direct.error.empty());

  arcos::PacketDecoder decoder;
  arcos::ArcosClientSession session;
  session.start(0.0);
  std::vector<arcos::Packet> packets;
  std::size_t delivered_bytes = 0;
  double now = 0.0;
  for (std::size_t i = 0; i < stream.size(); i += chunk) {
    packets.clear();
    decoder.feed(stream.subspan(i, std::min(chunk, stream.size() - i)), packets);
    for (const arcos::Packet& packet : packets) {
      IRGS_FUZZ_CHECK(packet.size >= 1 && packet.size <= arcos::kMaxPayload);
      delivered_bytes += packet.size + arcos::kOverhead;
      const auto parsed = arcos::parseStandardSip(packet.payload());
      if (parsed.sip) {
        const std::vector<std::uint8_t> again = arcos::encodeStandardSip(*parsed.sip);
        IRGS_FUZZ_CHECK(again.size() <= packet.size);
        const auto reparsed = arcos::parseStandardSip(again);
        IRGS_FUZZ_CHECK(reparsed.sip && *reparsed.sip == *parsed.sip);
      }
      session.onPacket(packet, now);
    }
    now += 0.05;
    session.tick(now);
    session.takeOutgoing();
    session.takeSips();
    session.takeEvents();
  }
  const arcos::PacketCounters& totals = decoder.totals();
  IRGS_FUZZ_CHECK(totals.garbage_bytes + delivered_bytes + decoder.bufferedBytes() ==
                  stream.size());
  return 0;
}
