// libFuzzer harness for the MAVLink FrameDecoder. The first input byte chooses the chunking and
// the signing configuration; the rest is the byte stream. Invariants checked on every input:
// no crash or sanitizer report, every byte accounted for (garbage, delivered frame or buffered),
// and delivered frames carry a payload no longer than their message allows; every entry of a
// delivered frame's field table (what the plots read) lies inside its payload and reads.
//
//   build/fuzz/irgs_fuzz_mavlink_decoder -max_total_time=60 fuzz/corpus/mavlink_decoder

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "comms/mavlink/field_info.hpp"
#include "comms/mavlink/frame_decoder.hpp"

namespace {

using irgs::comms::mavlink::DecoderConfig;
using irgs::comms::mavlink::findMessageInfo;
using irgs::comms::mavlink::Frame;
using irgs::comms::mavlink::FrameDecoder;
using irgs::comms::mavlink::ProtocolVersion;
using irgs::comms::mavlink::SigningKey;

std::size_t frameSize(const Frame& f) {
  namespace m = irgs::comms::mavlink;
  const std::size_t header =
      f.version == ProtocolVersion::kV2 ? m::kHeaderLengthV2 : m::kHeaderLengthV1;
  return header + f.payload_length + m::kChecksumLength + (f.is_signed ? m::kSignatureLength : 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  const std::uint8_t mode = data[0];
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  DecoderConfig config;
  config.accept_v1 = (mode & 0x01) == 0;
  if ((mode & 0x02) != 0) {
    config.signing_key = SigningKey{};  // all-zero key
    config.require_signed = (mode & 0x04) != 0;
  }
  FrameDecoder decoder(config);
  std::vector<Frame> frames;
  const std::size_t chunk = 1 + (mode >> 3);  // 1..32 bytes per feed
  for (std::size_t i = 0; i < stream.size(); i += chunk) {
    decoder.feed(stream.subspan(i, std::min(chunk, stream.size() - i)), frames);
  }
  std::size_t in_frames = 0;
  for (const Frame& f : frames) {
    const auto info = findMessageInfo(f.message_id);
    if (!info || f.payload_length > info->max_length) {
      std::abort();
    }
    in_frames += frameSize(f);
    namespace m = irgs::comms::mavlink;
    const m::MessageFields* table = m::findMessageFields(f.message_id);
    if (table == nullptr) {
      std::abort();  // every known message has a table
    }
    volatile double sink = 0.0;
    for (const m::FieldInfo& field : table->fields) {
      if (field.offset + m::sizeOf(field.type) > info->max_length) {
        std::abort();
      }
      sink = sink + m::readField(field, f);
    }
  }
  if (decoder.totals().garbage_bytes + in_frames + decoder.bufferedBytes() > stream.size()) {
    std::abort();
  }
  return 0;
}
