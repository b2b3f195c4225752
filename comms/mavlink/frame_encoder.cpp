#include "comms/mavlink/frame_encoder.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "comms/mavlink/crc.hpp"

namespace irgs::comms::mavlink {
namespace {

void checkPayload(const MessageInfo& info, std::span<const std::uint8_t> payload) {
  if (payload.size() > info.max_length) {
    throw std::invalid_argument("MAVLink payload of " + std::string(info.name) + " is " +
                                std::to_string(payload.size()) + " bytes, at most " +
                                std::to_string(info.max_length) + " allowed");
  }
}

void putChecksum(std::uint8_t* out, std::uint16_t crc) {
  out[0] = static_cast<std::uint8_t>(crc & 0xFF);
  out[1] = static_cast<std::uint8_t>(crc >> 8);
}

}  // namespace

std::size_t encodeFrame(std::span<std::uint8_t, kMaxFrameLength> out, const MessageInfo& info,
                        std::span<const std::uint8_t> payload, const FrameHeaderFields& header,
                        const SignatureFields* signature) {
  checkPayload(info, payload);
  // Trailing-zero truncation; the first payload byte is always sent.
  std::size_t length = payload.size();
  while (length > 1 && payload[length - 1] == 0) {
    --length;
  }
  if (length == 0) {  // zero-length messages do not exist, but never emit len 0
    length = 1;
  }
  std::uint8_t* p = out.data();
  p[0] = kStxV2;
  p[1] = static_cast<std::uint8_t>(length);
  p[2] = signature != nullptr ? kIncompatFlagSigned : 0;
  p[3] = header.compat_flags;
  p[4] = header.sequence;
  p[5] = header.system_id;
  p[6] = header.component_id;
  p[7] = static_cast<std::uint8_t>(info.id & 0xFF);
  p[8] = static_cast<std::uint8_t>((info.id >> 8) & 0xFF);
  p[9] = static_cast<std::uint8_t>((info.id >> 16) & 0xFF);
  std::fill_n(p + kHeaderLengthV2, length, std::uint8_t{0});
  std::copy_n(payload.data(), std::min(length, payload.size()), p + kHeaderLengthV2);
  std::uint16_t crc =
      crcAccumulate(std::span<const std::uint8_t>(p + 1, kHeaderLengthV2 - 1 + length));
  crc = crcAccumulate(info.crc_extra, crc);
  std::size_t size = kHeaderLengthV2 + length;
  putChecksum(p + size, crc);
  size += kChecksumLength;
  if (signature != nullptr) {
    p[size] = signature->link_id;
    const std::uint64_t ts = signature->timestamp & kSigningTimestampMask;
    for (std::size_t i = 0; i < 6; ++i) {
      p[size + 1 + i] = static_cast<std::uint8_t>(ts >> (8 * i));
    }
    size += 7;
    const Signature sig = computeSignature(signature->key, std::span<const std::uint8_t>(p, size));
    std::copy(sig.begin(), sig.end(), p + size);
    size += sig.size();
  }
  return size;
}

std::size_t encodeFrameV1(std::span<std::uint8_t, kMaxFrameLength> out, const MessageInfo& info,
                          std::span<const std::uint8_t> payload, const FrameHeaderFields& header) {
  checkPayload(info, payload);
  if (info.id > 255) {
    throw std::invalid_argument("MAVLink 1 cannot carry message id " + std::to_string(info.id));
  }
  const std::size_t length = info.min_length;
  std::uint8_t* p = out.data();
  p[0] = kStxV1;
  p[1] = static_cast<std::uint8_t>(length);
  p[2] = header.sequence;
  p[3] = header.system_id;
  p[4] = header.component_id;
  p[5] = static_cast<std::uint8_t>(info.id);
  std::fill_n(p + kHeaderLengthV1, length, std::uint8_t{0});
  std::copy_n(payload.data(), std::min(length, payload.size()), p + kHeaderLengthV1);
  std::uint16_t crc =
      crcAccumulate(std::span<const std::uint8_t>(p + 1, kHeaderLengthV1 - 1 + length));
  crc = crcAccumulate(info.crc_extra, crc);
  putChecksum(p + kHeaderLengthV1 + length, crc);
  return kHeaderLengthV1 + length + kChecksumLength;
}

FrameEncoder::FrameEncoder(std::uint8_t system_id, std::uint8_t component_id)
    : system_id_(system_id), component_id_(component_id) {}

void FrameEncoder::enableSigning(const SigningKey& key, std::uint8_t link_id) {
  key_ = key;
  link_id_ = link_id;
}

void FrameEncoder::disableSigning() {
  key_.reset();
}

EncodedFrame FrameEncoder::encodePayload(const MessageInfo& info,
                                         std::span<const std::uint8_t> payload,
                                         std::uint64_t signing_time) {
  EncodedFrame frame;
  const FrameHeaderFields header{sequence_, system_id_, component_id_, 0};
  if (key_) {
    // Strictly increasing per stream, or the receiver drops the frame as a replay.
    last_timestamp_ = std::max(signing_time & kSigningTimestampMask, last_timestamp_ + 1);
    const SignatureFields sig{*key_, link_id_, last_timestamp_};
    frame.size = encodeFrame(frame.bytes, info, payload, header, &sig);
  } else {
    frame.size = encodeFrame(frame.bytes, info, payload, header);
  }
  ++sequence_;
  return frame;
}

}  // namespace irgs::comms::mavlink
