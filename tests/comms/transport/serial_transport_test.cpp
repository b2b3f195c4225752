#include "comms/transport/serial_transport.hpp"

#include "transport_test_support.hpp"

#include <gtest/gtest.h>

#include <future>
#include <thread>

namespace irgs::comms {
namespace {

using testing::pattern;
using testing::PtyPair;
using testing::Recorder;

SerialOptions ptyOptions(const PtyPair& pty, std::uint32_t baud = 115200) {
  SerialOptions o;
  o.device = pty.slavePath();
  o.baud = baud;
  return o;
}

TEST(SerialTransport, CarriesBytesBothWaysOverAPtyAt115200) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto t = makeSerialTransport(io, ptyOptions(pty), rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kOpen)) << rec.allMessages();
  EXPECT_EQ(t->state(), TransportState::kOpen);

  const std::string hello = "hello robot";
  ASSERT_TRUE(t->send(testing::asBytes(hello)));
  std::vector<std::uint8_t> got;
  ASSERT_TRUE(pty.readExactly(hello.size(), got));
  EXPECT_EQ(testing::asText(got), hello);

  const auto reply = pattern(300, 1);
  ASSERT_TRUE(pty.writeAll(reply));
  ASSERT_TRUE(rec.waitBytes(reply.size()));
  EXPECT_EQ(rec.bytes(), reply);

  const auto s = t->stats();
  EXPECT_EQ(s.rx_bytes, reply.size());
  EXPECT_EQ(s.tx_bytes, hello.size());
  EXPECT_EQ(s.tx_dropped_bytes, 0u);
}

TEST(SerialTransport, TransfersLargeBlocksIntactInBothDirectionsAtOnce) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto options = ptyOptions(pty);
  options.tx_queue_bytes = 1 << 20;
  auto t = makeSerialTransport(io, options, rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kOpen)) << rec.allMessages();

  constexpr std::size_t kSize = 256 * 1024;
  const auto down = pattern(kSize, 2);  // ground station -> robot
  const auto up = pattern(kSize, 3);    // robot -> ground station
  auto writer = std::async(std::launch::async, [&] { return pty.writeAll(up); });
  for (std::size_t offset = 0; offset < kSize; offset += 1000) {
    const std::size_t n = std::min<std::size_t>(1000, kSize - offset);
    ASSERT_TRUE(t->send(std::span(down).subspan(offset, n)));
  }
  std::vector<std::uint8_t> received;
  ASSERT_TRUE(pty.readExactly(kSize, received));
  EXPECT_TRUE(received == down);
  ASSERT_TRUE(writer.get());
  ASSERT_TRUE(rec.waitBytes(kSize));
  EXPECT_TRUE(rec.bytes() == up);
}

TEST(SerialTransport, OpensAtEveryCommonBaudRateWithEitherFlowControl) {
  IoThread io;
  for (const std::uint32_t baud :
       {9600u, 19200u, 38400u, 57600u, 115200u, 230400u, 460800u, 921600u}) {
    for (const auto flow : {FlowControl::kNone, FlowControl::kHardware}) {
      PtyPair pty;
      Recorder rec;
      auto options = ptyOptions(pty, baud);
      options.flow = flow;
      auto t = makeSerialTransport(io, options, rec.callbacks());
      t->open();
      ASSERT_TRUE(rec.waitState(TransportState::kOpen)) << baud << ": " << rec.allMessages();
      termios tio{};
      ASSERT_EQ(::tcgetattr(pty.masterFd(), &tio), 0);
      EXPECT_EQ(tio.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
      EXPECT_EQ(tio.c_cflag & PARENB, 0u);
      EXPECT_EQ(tio.c_cflag & CSTOPB, 0u);
    }
  }
}

TEST(SerialTransport, FailsWithTheDeviceNameWhenThePtyMasterCloses) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto t = makeSerialTransport(io, ptyOptions(pty), rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kOpen)) << rec.allMessages();
  pty.closeMaster();
  ASSERT_TRUE(rec.waitState(TransportState::kFailed)) << rec.allMessages();
  EXPECT_EQ(t->state(), TransportState::kFailed);
  EXPECT_NE(rec.lastMessage().find(pty.slavePath()), std::string::npos) << rec.lastMessage();
  EXPECT_NE(rec.lastMessage().find("disappeared"), std::string::npos) << rec.lastMessage();
  EXPECT_FALSE(t->send(testing::asBytes("x")));
}

TEST(SerialTransport, ReportsAMissingDeviceAsFailedWithoutThrowing) {
  IoThread io;
  Recorder rec;
  SerialOptions o;
  o.device = "/dev/irgs-no-such-port";
  auto t = makeSerialTransport(io, o, rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kFailed));
  EXPECT_NE(rec.lastMessage().find("cannot open /dev/irgs-no-such-port"), std::string::npos)
      << rec.lastMessage();
}

TEST(SerialTransport, ReportsABaudRateTermiosDoesNotKnow) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto t = makeSerialTransport(io, ptyOptions(pty, 123457), rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kFailed));
  EXPECT_NE(rec.lastMessage().find("123457 baud"), std::string::npos) << rec.lastMessage();
}

TEST(SerialTransport, BoundsItsTransmitQueueAndCountsWhatItDrops) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto options = ptyOptions(pty);
  options.tx_queue_bytes = 4096;
  auto t = makeSerialTransport(io, options, rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kOpen)) << rec.allMessages();

  // Nobody reads the master: the pty buffer fills, then the queue, then send() refuses.
  std::vector<std::uint8_t> accepted;
  std::uint64_t refused = 0;
  for (std::uint32_t i = 0; i < 4000; ++i) {
    const auto chunk = pattern(512, i);
    if (t->send(chunk))
      accepted.insert(accepted.end(), chunk.begin(), chunk.end());
    else
      refused += chunk.size();
    EXPECT_LE(t->stats().tx_queued_bytes, options.tx_queue_bytes);
  }
  ASSERT_GT(refused, 0u);
  EXPECT_EQ(t->stats().tx_dropped_bytes, refused);

  // Everything accepted arrives, in order, once the reader catches up.
  std::vector<std::uint8_t> received;
  ASSERT_TRUE(pty.readExactly(accepted.size(), received));
  EXPECT_TRUE(received == accepted);
}

TEST(SerialTransport, CanBeReopenedAfterClose) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto t = makeSerialTransport(io, ptyOptions(pty), rec.callbacks());
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kOpen));
  t->close();
  ASSERT_TRUE(rec.waitState(TransportState::kClosed));
  t->open();
  ASSERT_TRUE(rec.waitState(TransportState::kOpen, 2)) << rec.allMessages();
  ASSERT_TRUE(t->send(testing::asBytes("again")));
  std::vector<std::uint8_t> got;
  ASSERT_TRUE(pty.readExactly(5, got));
  EXPECT_EQ(testing::asText(got), "again");
}

TEST(SerialTransport, MayBeDestroyedFromItsOwnFailureCallback) {
  IoThread io;
  PtyPair pty;
  std::unique_ptr<Transport> t;
  std::promise<void> opened;
  std::promise<void> destroyed;
  TransportCallbacks cb;
  cb.on_state = [&](TransportState state, const std::string&) {
    if (state == TransportState::kOpen)
      opened.set_value();
    if (state == TransportState::kFailed) {
      t.reset();  // the owner drops the link from inside the callback
      destroyed.set_value();
    }
  };
  t = makeSerialTransport(io, ptyOptions(pty), cb);
  t->open();
  ASSERT_EQ(opened.get_future().wait_for(testing::kWait), std::future_status::ready);
  pty.closeMaster();
  EXPECT_EQ(destroyed.get_future().wait_for(testing::kWait), std::future_status::ready);
}

TEST(SerialTransport, RunsNoCallbackAfterDestruction) {
  IoThread io;
  PtyPair pty;
  auto rec = std::make_unique<Recorder>();
  auto t = makeSerialTransport(io, ptyOptions(pty), rec->callbacks());
  t->open();
  ASSERT_TRUE(rec->waitState(TransportState::kOpen));
  ASSERT_TRUE(pty.writeAll(pattern(64, 4)));
  t.reset();
  rec.reset();  // any later callback would now touch freed memory (ASan would report it)
  pty.closeMaster();
}

}  // namespace
}  // namespace irgs::comms
