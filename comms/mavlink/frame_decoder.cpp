#include "comms/mavlink/frame_decoder.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "comms/mavlink/crc.hpp"

namespace irgs::comms::mavlink {
namespace {

// A new signing stream may start at most one minute before the newest time seen (spec rule 3
// for streams the receiver has not seen before).
constexpr std::uint64_t kNewStreamTolerance = 60 * kSigningTicksPerSecond;

bool isStx(std::uint8_t b, bool accept_v1) {
  return b == kStxV2 || (accept_v1 && b == kStxV1);
}

std::uint16_t readChecksum(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}

}  // namespace

DecodeCounters& DecodeCounters::operator+=(const DecodeCounters& o) {
  frames += o.frames;
  bad_crc += o.bad_crc;
  bad_length += o.bad_length;
  unknown_id += o.unknown_id;
  unsupported_flags += o.unsupported_flags;
  bad_signature += o.bad_signature;
  replay_rejected += o.replay_rejected;
  unsigned_rejected += o.unsigned_rejected;
  sequence_gaps += o.sequence_gaps;
  garbage_bytes += o.garbage_bytes;
  return *this;
}

FrameDecoder::FrameDecoder(DecoderConfig config) : config_(config) {
  if (!std::ranges::is_sorted(config_.messages, {}, &MessageInfo::id)) {
    throw std::invalid_argument("FrameDecoder: message table must be sorted by id");
  }
  frames_.reserve(32);
  senders_.reserve(16);
  streams_.reserve(16);
}

void FrameDecoder::reset() {
  begin_ = end_ = 0;
  senders_.clear();
  streams_.clear();
  newest_timestamp_ = 0;
}

void FrameDecoder::setSigningClock(std::uint64_t now) {
  newest_timestamp_ = std::max(newest_timestamp_, now);
}

void FrameDecoder::setSigningKey(std::optional<SigningKey> key, bool require_signed) {
  config_.signing_key = key;
  config_.require_signed = require_signed;
  streams_.clear();
}

DecodeResult FrameDecoder::feed(std::span<const std::uint8_t> bytes) {
  frames_.clear();
  const DecodeCounters counters = feed(bytes, frames_);
  return {frames_, counters};
}

DecodeCounters FrameDecoder::feed(std::span<const std::uint8_t> bytes, std::vector<Frame>& out) {
  DecodeCounters counters;
  std::size_t used = 0;
  while (used < bytes.size()) {
    if (begin_ > 0) {  // compact: the unparsed tail (< one frame) moves to the front
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    const std::size_t take = std::min(buffer_.size() - end_, bytes.size() - used);
    if (take == 0) {  // parse() leaves less than one frame buffered, so this cannot happen
      throw std::logic_error("FrameDecoder: buffer full without a complete frame");
    }
    std::memcpy(buffer_.data() + end_, bytes.data() + used, take);
    end_ += take;
    used += take;
    parse(out, counters);
  }
  totals_ += counters;
  return counters;
}

void FrameDecoder::parse(std::vector<Frame>& out, DecodeCounters& counters) {
  while (true) {
    const std::size_t start = begin_;
    while (begin_ < end_ && !isStx(buffer_[begin_], config_.accept_v1)) {
      ++begin_;
    }
    counters.garbage_bytes += begin_ - start;
    if (begin_ == end_) {
      return;
    }
    const Step step = parseOne(out, counters);
    if (step == Step::kNeedMore) {
      return;
    }
    if (step == Step::kRejected) {  // drop the false STX only: a frame may start inside
      ++begin_;
      ++counters.garbage_bytes;
    }
  }
}

FrameDecoder::Step FrameDecoder::parseOne(std::vector<Frame>& out, DecodeCounters& counters) {
  const std::uint8_t* p = buffer_.data() + begin_;
  const std::size_t available = end_ - begin_;
  const bool v2 = p[0] == kStxV2;
  const std::size_t header_length = v2 ? kHeaderLengthV2 : kHeaderLengthV1;
  if (available < header_length) {
    return Step::kNeedMore;
  }
  Frame f;
  f.payload_length = p[1];
  if (v2) {
    f.version = ProtocolVersion::kV2;
    f.incompat_flags = p[2];
    f.compat_flags = p[3];
    f.sequence = p[4];
    f.system_id = p[5];
    f.component_id = p[6];
    f.message_id = static_cast<std::uint32_t>(p[7] | (p[8] << 8) | (p[9] << 16));
    if ((f.incompat_flags & ~kKnownIncompatFlags) != 0) {
      ++counters.unsupported_flags;  // the spec forbids handling a frame with unknown flags
      return Step::kRejected;
    }
    f.is_signed = (f.incompat_flags & kIncompatFlagSigned) != 0;
  } else {
    f.version = ProtocolVersion::kV1;
    f.sequence = p[2];
    f.system_id = p[3];
    f.component_id = p[4];
    f.message_id = p[5];
  }
  const std::optional<MessageInfo> info = findMessageInfo(f.message_id, config_.messages);
  if (!info) {
    ++counters.unknown_id;
    return Step::kRejected;
  }
  // v2 payloads may be trimmed below the base length; v1 carries at least the base fields.
  const std::size_t min_length = v2 ? 0 : info->min_length;
  if (f.payload_length > info->max_length || f.payload_length < min_length) {
    ++counters.bad_length;
    return Step::kRejected;
  }
  const std::size_t crc_at = header_length + f.payload_length;
  const std::size_t size = crc_at + kChecksumLength + (f.is_signed ? kSignatureLength : 0);
  if (available < size) {
    return Step::kNeedMore;
  }
  std::uint16_t crc = crcAccumulate(std::span<const std::uint8_t>(p + 1, crc_at - 1));
  crc = crcAccumulate(info->crc_extra, crc);
  if (crc != readChecksum(p + crc_at)) {
    ++counters.bad_crc;
    return Step::kRejected;
  }
  // From here the frame boundaries are trusted: a rejected frame is skipped as a whole.
  begin_ += size;
  if (!acceptSignature(p, size, f, counters)) {
    return Step::kConsumed;
  }
  std::memcpy(f.payload.data(), p + header_length, f.payload_length);
  trackSequence(f, counters);
  ++counters.frames;
  out.push_back(f);
  return Step::kConsumed;
}

bool FrameDecoder::acceptSignature(const std::uint8_t* frame, std::size_t size, Frame& f,
                                   DecodeCounters& counters) {
  if (!f.is_signed) {
    if (config_.signing_key && config_.require_signed) {
      ++counters.unsigned_rejected;
      return false;
    }
    return true;
  }
  const std::uint8_t* sig = frame + size - kSignatureLength;
  f.link_id = sig[0];
  f.signature_timestamp = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    f.signature_timestamp |= static_cast<std::uint64_t>(sig[1 + i]) << (8 * i);
  }
  if (!config_.signing_key) {
    return true;  // cannot verify; delivered with signature_verified = false
  }
  const Signature expected = computeSignature(
      *config_.signing_key, std::span<const std::uint8_t>(frame, size - Signature{}.size()));
  if (!std::equal(expected.begin(), expected.end(), sig + 7)) {
    ++counters.bad_signature;
    return false;
  }
  const std::uint32_t key = (std::uint32_t{f.link_id} << 16) | (std::uint32_t{f.system_id} << 8) |
                            std::uint32_t{f.component_id};
  auto stream = std::ranges::find(streams_, key, &StreamState::key);
  if (stream == streams_.end()) {
    if (f.signature_timestamp + kNewStreamTolerance < newest_timestamp_) {
      ++counters.replay_rejected;
      return false;
    }
    streams_.push_back({key, f.signature_timestamp});
  } else {
    if (f.signature_timestamp <= stream->last_timestamp) {
      ++counters.replay_rejected;
      return false;
    }
    stream->last_timestamp = f.signature_timestamp;
  }
  newest_timestamp_ = std::max(newest_timestamp_, f.signature_timestamp);
  f.signature_verified = true;
  return true;
}

void FrameDecoder::trackSequence(const Frame& f, DecodeCounters& counters) {
  const auto key = static_cast<std::uint16_t>((f.system_id << 8) | f.component_id);
  auto sender = std::ranges::find(senders_, key, &SenderState::key);
  if (sender == senders_.end()) {
    senders_.push_back({key, f.sequence});
    return;
  }
  // A repeated sequence number is a duplicate, not 255 lost frames.
  if (f.sequence != sender->last_sequence) {
    counters.sequence_gaps += static_cast<std::uint8_t>(f.sequence - sender->last_sequence - 1);
  }
  sender->last_sequence = f.sequence;
}

}  // namespace irgs::comms::mavlink
