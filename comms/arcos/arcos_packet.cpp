#include "comms/arcos/arcos_packet.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace irgs::comms::arcos {

std::uint16_t checksum(std::span<const std::uint8_t> payload) {
  std::uint32_t sum = 0;
  std::size_t i = 0;
  for (; i + 1 < payload.size(); i += 2) {
    sum += static_cast<std::uint32_t>(payload[i] << 8 | payload[i + 1]);
    sum &= 0xFFFF;
  }
  if (i < payload.size())
    sum ^= payload[i];  // the odd-byte rule
  return static_cast<std::uint16_t>(sum);
}

std::vector<std::uint8_t> framePacket(std::span<const std::uint8_t> payload) {
  if (payload.empty() || payload.size() > kMaxPayload) {
    throw std::invalid_argument("ARCOS payload must be 1.." + std::to_string(kMaxPayload) +
                                " bytes, got " + std::to_string(payload.size()));
  }
  std::vector<std::uint8_t> packet;
  packet.reserve(payload.size() + kOverhead);
  packet.push_back(kHeader0);
  packet.push_back(kHeader1);
  packet.push_back(static_cast<std::uint8_t>(payload.size() + 2));
  packet.insert(packet.end(), payload.begin(), payload.end());
  const std::uint16_t sum = checksum(payload);
  packet.push_back(static_cast<std::uint8_t>(sum >> 8));
  packet.push_back(static_cast<std::uint8_t>(sum & 0xFF));
  return packet;
}

PacketCounters& PacketCounters::operator+=(const PacketCounters& other) {
  packets += other.packets;
  bad_checksum += other.bad_checksum;
  bad_count += other.bad_count;
  garbage_bytes += other.garbage_bytes;
  return *this;
}

void PacketDecoder::reset() {
  begin_ = 0;
  end_ = 0;
}

PacketCounters PacketDecoder::feed(std::span<const std::uint8_t> bytes, std::vector<Packet>& out) {
  PacketCounters counters;
  while (!bytes.empty()) {
    if (begin_ > 0 && (end_ == buffer_.size() || begin_ == end_)) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    const std::size_t take = std::min(bytes.size(), buffer_.size() - end_);
    std::memcpy(buffer_.data() + end_, bytes.data(), take);
    end_ += take;
    bytes = bytes.subspan(take);
    parse(out, counters);
  }
  totals_ += counters;
  return counters;
}

void PacketDecoder::parse(std::vector<Packet>& out, PacketCounters& counters) {
  while (begin_ < end_) {
    const std::uint8_t* data = buffer_.data() + begin_;
    const std::size_t available = end_ - begin_;
    if (data[0] != kHeader0) {
      // Skip to the next possible header byte in one go.
      const auto* next = static_cast<const std::uint8_t*>(std::memchr(data, kHeader0, available));
      const std::size_t skipped = next ? static_cast<std::size_t>(next - data) : available;
      counters.garbage_bytes += skipped;
      begin_ += skipped;
      continue;
    }
    if (available < 2)
      return;
    if (data[1] != kHeader1) {
      ++counters.garbage_bytes;
      ++begin_;
      continue;
    }
    if (available < 3)
      return;
    const std::size_t count = data[2];
    if (count < 3) {
      ++counters.bad_count;
      ++counters.garbage_bytes;
      ++begin_;
      continue;
    }
    const std::size_t total = 3 + count;
    if (available < total)
      return;
    const std::span<const std::uint8_t> payload(data + 3, count - 2);
    const auto received = static_cast<std::uint16_t>(data[total - 2] << 8 | data[total - 1]);
    if (checksum(payload) != received) {
      ++counters.bad_checksum;
      ++counters.garbage_bytes;
      ++begin_;
      continue;
    }
    Packet& packet = out.emplace_back();
    std::memcpy(packet.bytes.data(), payload.data(), payload.size());
    packet.size = payload.size();
    ++counters.packets;
    begin_ += total;
  }
}

}  // namespace irgs::comms::arcos
