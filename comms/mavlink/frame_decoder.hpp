#pragma once
// Turning a byte stream into checked MAVLink frames.
//
// feed() takes any slice of the stream (one byte or megabytes), returns the frames completed by
// it and counts what went wrong. Bytes are copied into a fixed 2-frame buffer; the only
// allocations are the output vector growing past its reserve and the first frame of a new
// sender or signing stream (a few bytes each), never per byte.
//
// Resynchronisation: when a candidate frame fails (unsupported flags, unknown id, bad length,
// bad CRC) only its start byte is dropped and the search for STX resumes right after it, so a
// real frame that begins inside a false start is still found. Consequently `garbage_bytes` is
// every byte that was not part of a frame with a valid checksum. A frame whose id is unknown
// cannot be checked, so it is treated the same way (its bytes count as garbage).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/message_info.hpp"
#include "comms/mavlink/signing.hpp"

namespace irgs::comms::mavlink {

struct DecoderConfig {
  // Known messages, sorted by id; must outlive the decoder. Default: everything generated.
  std::span<const MessageInfo> messages = generatedMessages();
  bool accept_v1 = true;
  // With a key, signatures are verified and replays (a timestamp not above the last one of the
  // same (link id, system id, component id) stream) are dropped; without one, signed frames are
  // delivered unverified.
  std::optional<SigningKey> signing_key{};
  bool require_signed = false;  // with a key: drop unsigned frames
};

struct DecodeCounters {
  std::uint64_t frames = 0;             // delivered
  std::uint64_t bad_crc = 0;            // checksum mismatch
  std::uint64_t bad_length = 0;         // payload length impossible for the message id
  std::uint64_t unknown_id = 0;         // id not in the message table (cannot be checked)
  std::uint64_t unsupported_flags = 0;  // incompat flags this decoder does not implement
  std::uint64_t bad_signature = 0;      // signed, checksum fine, signature wrong for our key
  std::uint64_t replay_rejected = 0;    // signature fine, timestamp not increasing / too old
  std::uint64_t unsigned_rejected = 0;  // unsigned while require_signed
  std::uint64_t sequence_gaps = 0;      // frames missing according to per-sender sequence numbers
  std::uint64_t garbage_bytes = 0;      // bytes not part of any frame with a valid checksum

  DecodeCounters& operator+=(const DecodeCounters& other);
  friend bool operator==(const DecodeCounters&, const DecodeCounters&) = default;
};

struct DecodeResult {
  std::span<const Frame> frames;  // valid until the next feed()
  DecodeCounters counters;        // of this feed() only; FrameDecoder::totals() sums them
};

class FrameDecoder {
 public:
  // Throws std::invalid_argument when config.messages is not sorted by id.
  explicit FrameDecoder(DecoderConfig config = {});

  DecodeResult feed(std::span<const std::uint8_t> bytes);
  // Appends the completed frames to `out` (which the caller clears and reuses).
  DecodeCounters feed(std::span<const std::uint8_t> bytes, std::vector<Frame>& out);

  const DecodeCounters& totals() const { return totals_; }
  std::size_t bufferedBytes() const { return end_ - begin_; }
  // Forgets the buffered partial frame and all per-sender state (after a reconnect).
  void reset();

  void setSigningKey(std::optional<SigningKey> key, bool require_signed);
  // The receiver's own signing clock (signingTimestampAt(now)): a new signing stream whose first
  // timestamp is more than 60 s older than this (or than the newest verified timestamp) is a
  // replay. Without it a freshly started receiver would accept a recording of any age. Never
  // moves the clock back.
  void setSigningClock(std::uint64_t now);

 private:
  enum class Step { kNeedMore, kRejected, kConsumed };
  Step parseOne(std::vector<Frame>& out, DecodeCounters& counters);
  void parse(std::vector<Frame>& out, DecodeCounters& counters);
  bool acceptSignature(const std::uint8_t* frame, std::size_t size, Frame& f,
                       DecodeCounters& counters);
  void trackSequence(const Frame& f, DecodeCounters& counters);

  struct SenderState {
    std::uint16_t key = 0;  // sysid << 8 | compid
    std::uint8_t last_sequence = 0;
  };
  struct StreamState {
    std::uint32_t key = 0;  // link id << 16 | sysid << 8 | compid
    std::uint64_t last_timestamp = 0;
  };

  DecoderConfig config_;
  std::array<std::uint8_t, 2 * kMaxFrameLength> buffer_{};
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  std::vector<Frame> frames_;
  std::vector<SenderState> senders_;
  std::vector<StreamState> streams_;
  std::uint64_t newest_timestamp_ = 0;  // newest verified signing time seen (the local clock)
  DecodeCounters totals_;
};

}  // namespace irgs::comms::mavlink
