#include "comms/mavlink/crc.hpp"

#include <gtest/gtest.h>

#include <array>

namespace irgs::comms::mavlink {
namespace {

TEST(MavlinkCrc, MatchesTheMcrf4xxCheckValue) {
  // CRC-16/MCRF4XX catalogue check value.
  EXPECT_EQ(crcAccumulate(std::string_view("123456789")), 0x6F91);
}

TEST(MavlinkCrc, OfNothingIsTheInitialValue) {
  EXPECT_EQ(crcAccumulate(std::span<const std::uint8_t>{}), kCrcInit);
}

TEST(MavlinkCrc, AccumulatesAcrossPieces) {
  const std::array<std::uint8_t, 4> bytes{0xFD, 0x09, 0x00, 0x42};
  std::uint16_t crc = kCrcInit;
  for (const std::uint8_t b : bytes) {
    crc = crcAccumulate(b, crc);
  }
  EXPECT_EQ(crc, crcAccumulate(bytes));
  EXPECT_EQ(crcAccumulate(std::span(bytes).subspan(2), crcAccumulate(std::span(bytes).first(2))),
            crc);
}

TEST(MavlinkCrc, FoldsToCrcExtraByXoringBothBytes) {
  EXPECT_EQ(foldCrcExtra(0x1234), 0x12 ^ 0x34);
  EXPECT_EQ(foldCrcExtra(0xFF00), 0xFF);
}

}  // namespace
}  // namespace irgs::comms::mavlink
