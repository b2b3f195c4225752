#include "comms/transport/udp_transport.hpp"

#include "transport_test_support.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

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

// A listener that echoes every datagram to its peer (as a robot replying to its ground station),
// and senders on loopback.
struct EchoListener {
  Recorder rec;
  std::unique_ptr<Transport> transport;
  EchoListener(IoThread& io, PeerPolicy peers) {
    auto callbacks = rec.callbacks();
    callbacks.on_bytes = [this, record = callbacks.on_bytes](std::span<const std::uint8_t> bytes) {
      record(bytes);
      transport->send(bytes);
    };
    UdpOptions o;
    o.listen = true;
    o.port = 0;  // host empty: loopback
    o.peers = std::move(peers);
    transport = makeUdpTransport(io, o, callbacks);
    transport->open();
  }
  ~EchoListener() { transport.reset(); }  // before the recorder its callbacks use
};

struct Sender {
  Recorder rec;
  std::unique_ptr<Transport> transport;
  Sender(IoThread& io, std::uint16_t port) {
    UdpOptions o;
    o.listen = false;
    o.host = "127.0.0.1";
    o.port = port;
    transport = makeUdpTransport(io, o, rec.callbacks());
    transport->open();
    EXPECT_TRUE(rec.waitState(TransportState::kOpen)) << rec.allMessages();
  }
};

// Issue 24, "who may drive": a second sender neither reaches the listener's owner nor takes the
// replies over while the first one is active.
TEST(UdpTransport, ListenerKeepsItsPeerAndRefusesAnotherSenderWhileThePeerIsActive) {
  IoThread io;
  EchoListener listener(io, {});  // default policy: active while it sent within 3 s
  ASSERT_TRUE(listener.rec.waitState(TransportState::kOpen)) << listener.rec.allMessages();
  EXPECT_NE(listener.rec.lastMessage().find("bound udp 127.0.0.1:"), std::string::npos)
      << listener.rec.lastMessage();
  const auto port = listener.transport->localPort();
  Sender first(io, port);
  Sender second(io, port);
  ASSERT_TRUE(first.transport->send(asBytes("a1")));
  ASSERT_TRUE(first.rec.waitBytes(2));
  ASSERT_TRUE(second.transport->send(asBytes("b1")));
  ASSERT_TRUE(listener.rec.waitRefused(1));
  EXPECT_EQ(listener.rec.refused().front(),
            "127.0.0.1:" + std::to_string(second.transport->localPort()));
  ASSERT_TRUE(first.transport->send(asBytes("a2")));
  ASSERT_TRUE(first.rec.waitBytes(4));
  EXPECT_EQ(asText(first.rec.bytes()), "a1a2");
  EXPECT_EQ(asText(listener.rec.bytes()), "a1a2");
  EXPECT_TRUE(second.rec.bytes().empty());
  EXPECT_EQ(listener.transport->stats().refused_peers, 1u);
}

TEST(UdpTransport, ListenerTakesANewPeerOnceThePolicySaysTheFirstHasGoneSilent) {
  IoThread io;
  std::atomic<bool> first_active{true};
  PeerPolicy peers;
  peers.peer_active = [&first_active] { return first_active.load(); };
  EchoListener listener(io, peers);
  ASSERT_TRUE(listener.rec.waitState(TransportState::kOpen));
  const auto port = listener.transport->localPort();
  Sender first(io, port);
  Sender second(io, port);
  ASSERT_TRUE(first.transport->send(asBytes("a1")));
  ASSERT_TRUE(first.rec.waitBytes(2));
  ASSERT_TRUE(second.transport->send(asBytes("b1")));
  ASSERT_TRUE(listener.rec.waitRefused(1));
  first_active = false;
  ASSERT_TRUE(second.transport->send(asBytes("b2")));
  ASSERT_TRUE(second.rec.waitBytes(2));
  EXPECT_EQ(asText(second.rec.bytes()), "b2");
  EXPECT_EQ(asText(listener.rec.bytes()), "a1b2");
}

TEST(UdpTransport, ListenerTakesANewPeerAfterThePeerTimeoutWithoutAPolicy) {
  IoThread io;
  PeerPolicy peers;
  peers.udp_peer_timeout = std::chrono::milliseconds(50);
  EchoListener listener(io, peers);
  ASSERT_TRUE(listener.rec.waitState(TransportState::kOpen));
  const auto port = listener.transport->localPort();
  Sender first(io, port);
  Sender second(io, port);
  ASSERT_TRUE(first.transport->send(asBytes("a1")));
  ASSERT_TRUE(first.rec.waitBytes(2));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // 4x the peer timeout
  ASSERT_TRUE(second.transport->send(asBytes("b1")));
  ASSERT_TRUE(second.rec.waitBytes(2));
  EXPECT_EQ(listener.transport->stats().refused_peers, 0u);
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
