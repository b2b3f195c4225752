#include "comms/transport/udp_transport.hpp"

#include "transport_test_support.hpp"

#include <gtest/gtest.h>

namespace irgs::comms {
namespace {

using testing::asBytes;
using testing::asText;
using testing::Recorder;

TEST(UdpTransport, ListenerEchoesToTheLastPeerOnLoopback) {
  IoThread io;
  std::unique_ptr<Transport> listener;
  Recorder listener_rec;
  auto callbacks = listener_rec.callbacks();
  auto record = callbacks.on_bytes;
  // Echo every datagram back, from the io thread, as a robot replying to its ground station.
  callbacks.on_bytes = [&, record](std::span<const std::uint8_t> bytes) {
    record(bytes);
    listener->send(bytes);
  };
  UdpOptions lo;
  lo.listen = true;
  lo.host = "127.0.0.1";
  lo.port = 0;
  listener = makeUdpTransport(io, lo, callbacks);
  listener->open();
  ASSERT_TRUE(listener_rec.waitState(TransportState::kOpen)) << listener_rec.allMessages();
  const auto port = listener->localPort();
  ASSERT_NE(port, 0);
  EXPECT_FALSE(listener->send(asBytes("no peer yet")));
  EXPECT_EQ(listener->stats().tx_dropped_bytes, 11u);

  Recorder sender_rec;
  UdpOptions so;
  so.listen = false;
  so.host = "127.0.0.1";
  so.port = port;
  auto sender = makeUdpTransport(io, so, sender_rec.callbacks());
  sender->open();
  ASSERT_TRUE(sender_rec.waitState(TransportState::kOpen)) << sender_rec.allMessages();
  ASSERT_TRUE(sender->send(asBytes("ping")));
  ASSERT_TRUE(sender->send(asBytes("pong!")));
  ASSERT_TRUE(sender_rec.waitBytes(9));
  EXPECT_EQ(asText(sender_rec.bytes()), "pingpong!");
  EXPECT_EQ(asText(listener_rec.bytes()), "pingpong!");
  EXPECT_EQ(listener->stats().rx_bytes, 9u);
  EXPECT_EQ(sender->stats().tx_bytes, 9u);
  listener.reset();
}

TEST(UdpTransport, ReportsAPortThatIsAlreadyTaken) {
  IoThread io;
  Recorder first_rec;
  UdpOptions o;
  o.host = "127.0.0.1";
  o.port = 0;
  auto first = makeUdpTransport(io, o, first_rec.callbacks());
  first->open();
  ASSERT_TRUE(first_rec.waitState(TransportState::kOpen));
  o.port = first->localPort();
  Recorder second_rec;
  auto second = makeUdpTransport(io, o, second_rec.callbacks());
  second->open();
  ASSERT_TRUE(second_rec.waitState(TransportState::kFailed));
  EXPECT_NE(second_rec.lastMessage().find("cannot bind udp 127.0.0.1:" + std::to_string(o.port)),
            std::string::npos)
      << second_rec.lastMessage();
}

}  // namespace
}  // namespace irgs::comms
