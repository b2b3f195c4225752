#include "comms/link/link_url.hpp"

#include <gtest/gtest.h>

namespace irgs::comms {
namespace {

TEST(LinkUrl, ParsesSerialDeviceAndBaud) {
  const auto r = parseLinkUrl("serial:///dev/rfcomm0?baud=9600");
  ASSERT_TRUE(r.url) << r.error;
  EXPECT_EQ(r.url->scheme, LinkScheme::kSerial);
  EXPECT_EQ(r.url->device, "/dev/rfcomm0");
  EXPECT_EQ(r.url->baud, 9600u);
  EXPECT_TRUE(r.url->options.empty());
}

TEST(LinkUrl, ParsesTcpHostPortAndKeepsUnknownOptions) {
  const auto r = parseLinkUrl("tcp://localhost:8101?protocol=arcos");
  ASSERT_TRUE(r.url) << r.error;
  EXPECT_EQ(r.url->scheme, LinkScheme::kTcp);
  EXPECT_EQ(r.url->host, "localhost");
  EXPECT_EQ(r.url->port, 8101);
  EXPECT_EQ(r.url->options.at("protocol"), "arcos");
  EXPECT_EQ(r.url->toString(), "tcp://localhost:8101?protocol=arcos");
}

TEST(LinkUrl, ParsesUdpWithEmptyHost) {
  const auto r = parseLinkUrl("udp://:14550");
  ASSERT_TRUE(r.url) << r.error;
  EXPECT_EQ(r.url->host, "");
  EXPECT_EQ(r.url->port, 14550);
}

TEST(LinkUrl, TheBaudBehindALinkIsTheSerialBaudOrTheTcpBaudOption) {
  EXPECT_EQ(linkBaud(*parseLinkUrl("serial:///dev/ttyUSB0?baud=9600").url), 9600u);
  EXPECT_EQ(linkBaud(*parseLinkUrl("serial:///dev/ttyUSB0").url), 57600u);  // the default
  EXPECT_EQ(linkBaud(*parseLinkUrl("tcp://robot:8101?protocol=arcos&baud=38400").url), 38400u);
  EXPECT_EQ(linkBaud(*parseLinkUrl("tcp://robot:8101?protocol=arcos").url), std::nullopt);
  EXPECT_EQ(linkBaud(*parseLinkUrl("udp://:14550").url), std::nullopt);
  EXPECT_NE(parseLinkUrl("tcp://robot:8101?baud=0").error.find("baud"), std::string::npos);
}

TEST(LinkUrl, RejectsBadInputWithAReason) {
  EXPECT_FALSE(parseLinkUrl("ttyUSB0").url);
  EXPECT_NE(parseLinkUrl("serial:///dev/ttyUSB0?baud=fast").error.find("baud"), std::string::npos);
  EXPECT_NE(parseLinkUrl("tcp://host").error.find("port"), std::string::npos);
  EXPECT_NE(parseLinkUrl("tcp://host:99999").error.find("port"), std::string::npos);
  EXPECT_NE(parseLinkUrl("ftp://x:1").error.find("scheme"), std::string::npos);
}

}  // namespace
}  // namespace irgs::comms
