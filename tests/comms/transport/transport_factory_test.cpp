#include "comms/transport/transport_factory.hpp"

#include "transport_test_support.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace irgs::comms {
namespace {

using testing::PtyPair;
using testing::Recorder;

LinkUrl url(const std::string& text) {
  auto r = parseLinkUrl(text);
  if (!r.url)
    throw std::invalid_argument(r.error);
  return *r.url;
}

TEST(TransportFactory, OpensASerialUrlOnAPtyWithBaudAndFlowControl) {
  IoThread io;
  PtyPair pty;
  Recorder rec;
  auto t = openTransport(url("serial://" + pty.slavePath() + "?baud=115200&flow=rtscts"), io,
                         rec.callbacks());
  ASSERT_TRUE(rec.waitState(TransportState::kOpen)) << rec.allMessages();
  EXPECT_EQ(t->description(), "serial " + pty.slavePath() + " @115200");
  termios tio{};
  ASSERT_EQ(::tcgetattr(pty.masterFd(), &tio), 0);
  EXPECT_NE(tio.c_cflag & CRTSCTS, 0u);
  ASSERT_TRUE(t->send(testing::asBytes("ok")));
  std::vector<std::uint8_t> got;
  ASSERT_TRUE(pty.readExactly(2, got));
  EXPECT_EQ(testing::asText(got), "ok");
}

TEST(TransportFactory, BuildsEachKindFromItsUrl) {
  IoThread io;
  const auto describe = [&](const std::string& text) {
    auto r = makeTransport(url(text), io);
    EXPECT_TRUE(r.transport) << text << ": " << r.error;
    return r.transport ? r.transport->description() : std::string{};
  };
  EXPECT_EQ(describe("serial:///dev/rfcomm0?baud=9600"), "serial /dev/rfcomm0 @9600");
  EXPECT_EQ(describe("tcp://192.168.4.1:5760"), "tcp client 192.168.4.1:5760");
  EXPECT_EQ(describe("tcp://:5760"), "tcp client 127.0.0.1:5760");
  EXPECT_EQ(describe("udp://127.0.0.1:14550?listen=1"), "udp listener 127.0.0.1:14550");
  EXPECT_EQ(describe("udp://10.0.0.5:14555?bind=14550"), "udp to 10.0.0.5:14555");
}

// Issue 24, "who may drive": a listener is reachable from this computer only, unless the URL
// names an address to bind.
TEST(TransportFactory, ListenersBindLoopbackUnlessAnAddressIsGiven) {
  IoThread io;
  const auto describe = [&](const std::string& text) {
    auto r = makeTransport(url(text), io);
    EXPECT_TRUE(r.transport) << text << ": " << r.error;
    return r.transport ? r.transport->description() : std::string{};
  };
  EXPECT_EQ(describe("tcp://:5760?listen=1"), "tcp server 127.0.0.1:5760");
  EXPECT_EQ(describe("tcp://0.0.0.0:5760?listen=1"), "tcp server 0.0.0.0:5760");
  EXPECT_EQ(describe("tcp://192.168.4.2:5760?listen=1"), "tcp server 192.168.4.2:5760");
  EXPECT_EQ(describe("udp://:14550"), "udp listener 127.0.0.1:14550");
  EXPECT_EQ(describe("udp://0.0.0.0:14550"), "udp listener 0.0.0.0:14550");
  EXPECT_EQ(describe("udp://0.0.0.0:14550?peer_timeout_ms=500"), "udp listener 0.0.0.0:14550");
}

TEST(TransportFactory, ReportsBadOptionValuesAsErrors) {
  IoThread io;
  const auto error = [&](const std::string& text) {
    auto r = makeTransport(url(text), io);
    EXPECT_FALSE(r.transport) << text;
    return r.error;
  };
  EXPECT_NE(error("serial:///dev/ttyUSB0?flow=xonxoff").find("flow='xonxoff'"), std::string::npos);
  EXPECT_NE(error("tcp://h:1?listen=maybe").find("listen='maybe'"), std::string::npos);
  EXPECT_NE(error("tcp://h:1?timeout_ms=-5").find("timeout_ms='-5'"), std::string::npos);
  EXPECT_NE(error("udp://h:1?bind=70000").find("bind='70000'"), std::string::npos);
  EXPECT_NE(error("udp://:1?listen=0").find("needs a host"), std::string::npos);
  EXPECT_NE(error("udp://:1?txq=1").find("txq='1'"), std::string::npos);
  EXPECT_NE(error("udp://:1?peer_timeout_ms=0").find("peer_timeout_ms='0'"), std::string::npos);
  EXPECT_THROW(openTransport(url("serial:///dev/ttyUSB0?flow=x"), io), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
