#include "comms/transport/tcp_transport.hpp"

#include "transport_test_support.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <future>
#include <utility>

#include <boost/asio/post.hpp>

namespace irgs::comms {
namespace {

using testing::asBytes;
using testing::asText;
using testing::pattern;
using testing::Recorder;

struct Server {
  Recorder rec;
  std::unique_ptr<Transport> transport;
  Server(IoThread& io, std::uint16_t port, PeerPolicy peers = {}, std::string host = "127.0.0.1") {
    TcpServerOptions o;
    o.host = std::move(host);
    o.port = port;
    o.peers = std::move(peers);
    transport = makeTcpServerTransport(io, o, rec.callbacks());
    transport->open();
  }
  std::uint16_t port() {
    EXPECT_TRUE(rec.waitMessage("listening on")) << rec.allMessages();
    return transport->localPort();
  }
};

struct Client {
  Recorder rec;
  std::unique_ptr<Transport> transport;
  Client(IoThread& io, std::uint16_t port,
         std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    TcpClientOptions o;
    o.host = "127.0.0.1";
    o.port = port;
    o.connect_timeout = timeout;
    transport = makeTcpClientTransport(io, o, rec.callbacks());
    transport->open();
  }
};

TEST(TcpTransport, ClientAndServerExchangeBytesOnAnEphemeralLoopbackPort) {
  IoThread io;
  Server server(io, 0);
  const auto port = server.port();
  ASSERT_NE(port, 0);
  EXPECT_EQ(server.transport->state(), TransportState::kOpening);
  EXPECT_FALSE(server.transport->send(asBytes("nobody listens")));

  Client client(io, port);
  ASSERT_TRUE(client.rec.waitState(TransportState::kOpen)) << client.rec.allMessages();
  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen)) << server.rec.allMessages();

  const auto up = pattern(10000, 5);
  ASSERT_TRUE(client.transport->send(std::span(up).first(10000)));
  ASSERT_TRUE(server.transport->send(asBytes("ack")));
  ASSERT_TRUE(client.rec.waitBytes(3));
  EXPECT_EQ(asText(client.rec.bytes()), "ack");
  ASSERT_TRUE(server.rec.waitBytes(10000));
  const auto got = server.rec.bytes();
  EXPECT_TRUE(std::equal(got.begin(), got.begin() + 10000, up.begin()));
}

TEST(TcpTransport, ClientReconnectsAfterTheServerRestartsOnTheSamePort) {
  IoThread io;
  auto server = std::make_unique<Server>(io, 0);
  const auto port = server->port();
  Client client(io, port);
  ASSERT_TRUE(client.rec.waitState(TransportState::kOpen)) << client.rec.allMessages();
  ASSERT_TRUE(server->rec.waitState(TransportState::kOpen));

  server.reset();  // server process goes away
  ASSERT_TRUE(client.rec.waitState(TransportState::kFailed)) << client.rec.allMessages();
  EXPECT_NE(client.rec.lastMessage().find("lost"), std::string::npos) << client.rec.lastMessage();

  server = std::make_unique<Server>(io, port);
  ASSERT_EQ(server->port(), port);
  client.transport->open();  // what the link manager does after a failure
  ASSERT_TRUE(client.rec.waitState(TransportState::kOpen, 2)) << client.rec.allMessages();
  ASSERT_TRUE(server->rec.waitState(TransportState::kOpen));
  ASSERT_TRUE(client.transport->send(asBytes("back")));
  ASSERT_TRUE(server->rec.waitBytes(4));
  EXPECT_EQ(asText(server->rec.bytes()), "back");
}

// Issue 24, "who may drive": a second client never takes over the connected one unannounced.
TEST(TcpTransport, ServerRefusesASecondClientWhileTheFirstIsConnected) {
  IoThread io;
  Server server(io, 0);
  const auto port = server.port();
  Client first(io, port);
  ASSERT_TRUE(first.rec.waitState(TransportState::kOpen));
  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen));
  ASSERT_TRUE(first.transport->send(asBytes("one")));
  ASSERT_TRUE(server.rec.waitBytes(3));

  Client second(io, port);
  ASSERT_TRUE(second.rec.waitState(TransportState::kOpen));  // the OS accepts, then we close
  second.transport->send(asBytes("two"));
  ASSERT_TRUE(server.rec.waitRefused(1)) << server.rec.allMessages();
  ASSERT_TRUE(second.rec.waitState(TransportState::kFailed)) << second.rec.allMessages();
  EXPECT_EQ(server.rec.refused().front(),
            "127.0.0.1:" + std::to_string(second.transport->localPort()));
  EXPECT_EQ(server.transport->stats().refused_peers, 1u);
  EXPECT_EQ(server.rec.count(TransportState::kOpen), 1u) << server.rec.allMessages();

  // The first client still has the server, and nothing of the second one was delivered.
  ASSERT_TRUE(first.transport->send(asBytes("ONE")));
  ASSERT_TRUE(server.rec.waitBytes(6));
  EXPECT_EQ(asText(server.rec.bytes()), "oneONE");
  ASSERT_TRUE(server.transport->send(asBytes("to first")));
  ASSERT_TRUE(first.rec.waitBytes(8));
  EXPECT_EQ(asText(first.rec.bytes()), "to first");
  EXPECT_EQ(first.transport->state(), TransportState::kOpen);
  EXPECT_TRUE(second.rec.bytes().empty());
}

TEST(TcpTransport, ARefusedClientReadsTheRefusalBytesBeforeItsConnectionCloses) {
  IoThread io;
  PeerPolicy peers;
  peers.refusal_bytes = [](const std::string& peer) {
    const std::string text = "busy, refused " + peer;
    return std::vector<std::uint8_t>(text.begin(), text.end());
  };
  Server server(io, 0, peers);
  const auto port = server.port();
  Client first(io, port);
  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen));
  Client second(io, port);
  ASSERT_TRUE(second.rec.waitState(TransportState::kOpen));
  // It keeps sending (unread input must not turn the close into a reset that eats the refusal).
  for (int i = 0; i < 50; ++i)
    second.transport->send(asBytes("frame frame frame"));
  ASSERT_TRUE(second.rec.waitState(TransportState::kFailed)) << second.rec.allMessages();
  const std::string expected =
      "busy, refused 127.0.0.1:" + std::to_string(second.transport->localPort());
  EXPECT_EQ(asText(second.rec.bytes()), expected);
  EXPECT_TRUE(first.rec.bytes().empty());
}

TEST(TcpTransport, ServerTakesANewClientWhenTheConnectedOneHasGoneSilent) {
  IoThread io;
  std::atomic<bool> first_active{true};
  PeerPolicy peers;
  peers.peer_active = [&first_active] { return first_active.load(); };
  Server server(io, 0, peers);
  const auto port = server.port();
  Client first(io, port);
  ASSERT_TRUE(first.rec.waitState(TransportState::kOpen));
  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen));
  {
    Client refused(io, port);
    ASSERT_TRUE(server.rec.waitRefused(1));
  }

  first_active = false;  // e.g. irgs-robot: no ground-station heartbeat for its timeout
  Client second(io, port);
  ASSERT_TRUE(server.rec.waitMessage("had gone silent")) << server.rec.allMessages();
  ASSERT_TRUE(first.rec.waitState(TransportState::kFailed)) << first.rec.allMessages();
  ASSERT_TRUE(server.transport->send(asBytes("to second")));
  ASSERT_TRUE(second.rec.waitBytes(9));
  EXPECT_EQ(asText(second.rec.bytes()), "to second");
  EXPECT_TRUE(first.rec.bytes().empty());
  EXPECT_EQ(server.transport->stats().refused_peers, 1u);
}

// A raw loopback connection (no transport, so the test controls exactly when it closes).
int connectRaw(std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
    return -1;
  return fd;
}

// A client that reconnects at once: its new connection and the end of its old one reach the
// server in the same instant (here: while the io thread is held), and the server must not refuse
// the client's return because of its own old connection.
TEST(TcpTransport, AClientReconnectingAtOnceIsNotRefusedForItsOldConnection) {
  IoThread io;
  PeerPolicy peers;
  peers.peer_active = [] { return true; };  // e.g. its heartbeats are recent
  Server server(io, 0, peers);
  const auto port = server.port();
  const int old_fd = connectRaw(port);
  ASSERT_GE(old_fd, 0);
  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen));

  std::promise<void> release;
  std::promise<void> held;
  boost::asio::post(io.context(), [&] {
    held.set_value();
    release.get_future().wait();
  });
  held.get_future().wait();
  // New connection first (the kernel completes the handshake meanwhile), then the old one
  // closes: the accept is then ready before the old socket's end of stream.
  const int new_fd = connectRaw(port);
  ::close(old_fd);
  release.set_value();
  ASSERT_GE(new_fd, 0);

  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen, 2)) << server.rec.allMessages();
  EXPECT_TRUE(server.rec.refused().empty()) << server.rec.allMessages();
  ASSERT_TRUE(server.transport->send(asBytes("back")));
  char buf[4] = {};
  pollfd p{new_fd, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 10000), 1);
  EXPECT_EQ(::recv(new_fd, buf, sizeof buf, MSG_WAITALL), 4);
  EXPECT_EQ(std::string(buf, 4), "back");
  ::close(new_fd);
}

TEST(TcpTransport, ServerListensOnLoopbackUnlessGivenAnAddress) {
  IoThread io;
  Server loopback(io, 0, {}, "");
  ASSERT_TRUE(loopback.rec.waitMessage("listening on 127.0.0.1:")) << loopback.rec.allMessages();
  EXPECT_EQ(loopback.transport->description(), "tcp server 127.0.0.1:0");
  Server every(io, 0, {}, "0.0.0.0");
  ASSERT_TRUE(every.rec.waitMessage("listening on 0.0.0.0:")) << every.rec.allMessages();
  // Reachable on loopback in both cases.
  Client client(io, every.transport->localPort());
  ASSERT_TRUE(every.rec.waitState(TransportState::kOpen)) << every.rec.allMessages();
}

TEST(TcpTransport, ServerKeepsListeningWhenItsClientLeaves) {
  IoThread io;
  Server server(io, 0);
  const auto port = server.port();
  {
    Client client(io, port);
    ASSERT_TRUE(server.rec.waitState(TransportState::kOpen));
  }
  ASSERT_TRUE(server.rec.waitMessage("left")) << server.rec.allMessages();
  EXPECT_EQ(server.transport->state(), TransportState::kOpening);
  Client again(io, port);
  ASSERT_TRUE(server.rec.waitState(TransportState::kOpen, 2)) << server.rec.allMessages();
}

TEST(TcpTransport, ClientFailsClearlyWhenNothingListens) {
  IoThread io;
  std::uint16_t port = 0;
  {
    Server probe(io, 0);  // find a free port, then release it
    port = probe.port();
  }
  Client client(io, port);
  ASSERT_TRUE(client.rec.waitState(TransportState::kFailed));
  EXPECT_NE(client.rec.lastMessage().find("cannot connect to 127.0.0.1:" + std::to_string(port)),
            std::string::npos)
      << client.rec.lastMessage();
}

TEST(TcpTransport, ClientConnectTimesOutWhenTheServerNeverAnswers) {
  // A listening socket with a full accept queue (backlog 0, never accepting) drops further SYNs,
  // so a connect to it hangs until our timeout fires.
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(listener, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(listener, 0), 0);
  socklen_t len = sizeof addr;
  ASSERT_EQ(::getsockname(listener, reinterpret_cast<sockaddr*>(&addr), &len), 0);
  const auto port = ntohs(addr.sin_port);

  IoThread io;
  std::vector<std::unique_ptr<Client>> fillers;
  // Fill the accept queue: connections complete until it is full.
  for (int i = 0; i < 8; ++i)
    fillers.push_back(std::make_unique<Client>(io, port, std::chrono::milliseconds(300)));
  std::size_t timed_out = 0;
  for (auto& f : fillers)
    ASSERT_TRUE(f->rec.waitSettled());
  for (auto& f : fillers) {
    if (f->rec.count(TransportState::kFailed) > 0 &&
        f->rec.lastMessage().find("timed out after 300 ms") != std::string::npos)
      ++timed_out;
  }
  EXPECT_GT(timed_out, 0u);
  fillers.clear();
  ::close(listener);
}

}  // namespace
}  // namespace irgs::comms
