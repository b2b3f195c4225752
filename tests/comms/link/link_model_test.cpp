#include "comms/link/link_model.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

namespace irgs::comms {
namespace {

std::vector<std::uint8_t> bytes(std::size_t n, std::uint8_t first = 0) {
  std::vector<std::uint8_t> v(n);
  std::iota(v.begin(), v.end(), first);
  return v;
}

TEST(LinkModel, DeliversAfterTheDelayInOrder) {
  LinkModel link({.delay_s = 0.15});
  link.send(bytes(3), 1.0);
  EXPECT_TRUE(link.receive(1.149).empty());
  EXPECT_EQ(link.receive(1.15), bytes(3));
  EXPECT_EQ(link.stats().bytes_out, 3u);
}

TEST(LinkModel, SerialisesBytesAtTheBaudRate) {
  // 9600 baud, 8N1: 960 bytes a second, one every 1.0417 ms.
  LinkModel link({.baud = 9600.0});
  link.send(bytes(96), 0.0);
  EXPECT_EQ(link.receive(0.0505).size(), 48u);  // the 48th at 0.05
  EXPECT_EQ(link.receive(0.1005).size(), 48u);
  // A second write queues behind the first: the line is busy until 0.1 s.
  link.send(bytes(96), 0.05);
  EXPECT_EQ(link.receive(0.1505).size(), 48u);
  EXPECT_NEAR(*link.nextArrival_s(), 0.1 + 49.0 / 960.0, 1e-9);
}

TEST(LinkModel, JitterNeverReordersBytes) {
  LinkModel link({.delay_s = 0.1, .jitter_s = 0.5, .seed = 7});
  std::vector<std::uint8_t> sent;
  for (int i = 0; i < 200; ++i) {
    const auto chunk = bytes(2, static_cast<std::uint8_t>(2 * i));
    link.send(chunk, 0.01 * i);
    sent.insert(sent.end(), chunk.begin(), chunk.end());
  }
  EXPECT_EQ(link.receive(100.0), sent);
}

TEST(LinkModel, AStallHoldsDeliveriesAndReleasesThemInABurstAfter) {
  LinkModel link({.delay_s = 0.1, .stall_every_s = 20.0, .stall_s = 0.5});
  link.send(bytes(1), 19.95);  // due at 20.05, inside the stall [20, 20.5)
  link.send(bytes(1, 1), 20.3);
  EXPECT_TRUE(link.receive(20.49).empty());
  EXPECT_EQ(link.receive(20.5).size(), 2u);
  link.send(bytes(1), 30.0);  // between stalls: on time
  EXPECT_EQ(link.receive(30.1).size(), 1u);
}

TEST(LinkModel, WhatAStallHeldComesOutAtTheBaudAfterIt) {
  // 9600 baud: a byte every 1.04 ms. Ten bytes sent during the stall leave the far end one byte
  // time apart after it, as its UART puts them out, not all at 20.5 s.
  LinkModel link({.baud = 9600, .stall_every_s = 20.0, .stall_s = 0.5});
  link.send(bytes(10), 20.1);
  EXPECT_TRUE(link.receive(20.4999).empty());
  EXPECT_EQ(link.receive(20.5).size(), 1u);
  EXPECT_EQ(link.receive(20.5 + 4.5 * 10.0 / 9600).size(), 4u);
  EXPECT_EQ(link.receive(20.6).size(), 5u);
}

TEST(LinkModel, LossAndCorruptionAtTheirRatesSameSeedSameBytes) {
  const LinkModelConfig config{.loss = 0.01, .corruption = 0.02, .seed = 3};
  LinkModel a(config), b(config);
  const auto data = bytes(100000 % 256);
  for (int i = 0; i < 400; ++i) {
    a.send(data, i);
    b.send(data, i);
  }
  const auto got = a.receive(1000.0);
  EXPECT_EQ(got, b.receive(1000.0));
  const auto in = static_cast<double>(a.stats().bytes_in);
  EXPECT_NEAR(static_cast<double>(a.stats().lost) / in, 0.01, 0.002);
  EXPECT_NEAR(static_cast<double>(a.stats().corrupted) / in, 0.02, 0.003);
  EXPECT_EQ(got.size(), a.stats().bytes_in - a.stats().lost);
}

TEST(LinkModel, RejectsABadConfig) {
  EXPECT_THROW(LinkModel({.delay_s = -1.0}), std::invalid_argument);
  EXPECT_THROW(LinkModel({.loss = 1.5}), std::invalid_argument);
  EXPECT_THROW(LinkModel({.stall_every_s = 1.0, .stall_s = 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
