#pragma once
// A seeded fault injector for a MAVLink byte stream, with the ground truth the decoder's
// counters are checked against: which frames it damaged and how many bytes of the output are
// not part of an intact frame.
//
// Faults are applied per original byte with probability `rate`: a bit flip (one random bit),
// a dropped byte, or a byte inserted before it (one in eight inserted bytes is a v2 STX 0xFD,
// so false frame starts are common). An insertion before the first byte of a frame lies
// between frames and damages none; so do faults that leave the frame's bytes intact among some
// garbage (a start marker inserted right after its STX starts it anew). Every other fault
// damages the frame it falls in.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace irgs::comms::testing {

enum class FaultKind { kBitFlip, kDrop, kInsert, kMixed };

struct InjectedStream {
  std::vector<std::uint8_t> bytes;  // what goes on the wire
  std::vector<bool> damaged;        // per input frame
  std::vector<std::size_t> begin;   // per input frame: where its bytes start in `bytes`
  std::size_t flips = 0;
  std::size_t drops = 0;
  std::size_t inserts = 0;
  // Output bytes that belong to no intact frame: damaged frames as they went out plus bytes
  // inserted between frames. The decoder must count exactly these as garbage.
  std::size_t damaged_bytes = 0;
  // Of those, bytes equal to a start marker (0xFD, 0xFE): each is one false start the decoder
  // examines and rejects (bad CRC, bad length, unknown id or unsupported flags).
  std::size_t damaged_stx_bytes = 0;
  // Damaged frames whose first byte (their STX) survived unchanged.
  std::size_t damaged_with_stx = 0;

  std::size_t damagedFrames() const {
    std::size_t n = 0;
    for (const bool d : damaged)
      n += d ? 1u : 0u;
    return n;
  }
};

class FaultInjector {
 public:
  FaultInjector(FaultKind kind, double rate, std::uint32_t seed)
      : kind_(kind), rate_(rate), rng_(seed) {}

  // `frames`: the encoded frames, in sending order.
  InjectedStream inject(const std::vector<std::vector<std::uint8_t>>& frames) {
    InjectedStream out;
    out.damaged.assign(frames.size(), false);
    out.begin.assign(frames.size(), 0);
    std::vector<std::uint8_t> body;  // this frame's bytes as they go out
    for (std::size_t f = 0; f < frames.size(); ++f) {
      body.clear();
      bool damaged = false;
      bool stx_survived = true;

      for (std::size_t i = 0; i < frames[f].size(); ++i) {
        std::uint8_t byte = frames[f][i];
        if (chance()) {
          const FaultKind kind = pick();
          if (kind == FaultKind::kBitFlip) {
            byte = static_cast<std::uint8_t>(byte ^ (1u << (rng_() % 8)));
            ++out.flips;
          } else if (kind == FaultKind::kDrop) {
            ++out.drops;
          } else {
            const std::uint8_t inserted =
                rng_() % 8 == 0 ? std::uint8_t{0xFD} : static_cast<std::uint8_t>(rng_());
            ++out.inserts;
            if (i == 0) {  // between frames: garbage, but no frame is damaged
              out.bytes.push_back(inserted);
              countGarbage(out, inserted);
            } else {
              body.push_back(inserted);
            }
          }
          const bool hits_frame = kind != FaultKind::kInsert || i != 0;
          damaged = damaged || hits_frame;
          stx_survived = stx_survived && !(i == 0 && hits_frame);
          if (kind == FaultKind::kDrop)
            continue;
        }
        body.push_back(byte);
      }
      out.begin[f] = out.bytes.size();
      out.bytes.insert(out.bytes.end(), body.begin(), body.end());
      const auto& frame = frames[f];
      const auto intact = std::search(body.begin(), body.end(), frame.begin(), frame.end());
      if (damaged && intact != body.end()) {
        // The faults left the whole frame intact among some garbage (a start marker inserted
        // right after the STX starts it anew; a byte inserted before the last one equal to it
        // trails it): the decoder rightly delivers it, the other bytes are garbage.
        damaged = false;
        const auto first = static_cast<std::size_t>(intact - body.begin());
        for (std::size_t k = 0; k < body.size(); ++k)
          if (k < first || k >= first + frame.size())
            countGarbage(out, body[k]);
      }
      if (damaged) {
        out.damaged[f] = true;
        for (const std::uint8_t b : body)
          countGarbage(out, b);
        if (stx_survived)
          ++out.damaged_with_stx;
      }
    }
    return out;
  }

 private:
  bool chance() {
    // rate as a fraction of 2^32: mt19937's output sequence is the same on every platform.
    return static_cast<double>(rng_()) < rate_ * 4294967296.0;
  }
  FaultKind pick() {
    if (kind_ != FaultKind::kMixed)
      return kind_;
    switch (rng_() % 3) {
      case 0:
        return FaultKind::kBitFlip;
      case 1:
        return FaultKind::kDrop;
      default:
        return FaultKind::kInsert;
    }
  }
  static void countGarbage(InjectedStream& out, std::uint8_t byte) {
    ++out.damaged_bytes;
    if (byte == 0xFD || byte == 0xFE)
      ++out.damaged_stx_bytes;
  }

  FaultKind kind_;
  double rate_;
  std::mt19937 rng_;
};

}  // namespace irgs::comms::testing
