#pragma once
// Connection settings as a plain value, parsed from a URL:
//   serial:///dev/ttyUSB0?baud=115200      (also Bluetooth SPP: serial:///dev/rfcomm0)
//   tcp://host:5760                         (client)   tcp://:5760?listen=1 (server)
//   udp://:14550                            (listen)   udp://host:14550     (send to)
// Listeners bind loopback (127.0.0.1) unless an address is given: tcp://0.0.0.0:5760?listen=1
// and udp://0.0.0.0:14550 listen on every interface (comms/transport/transport_factory.hpp).
// Query parameters other than the known ones are kept in `options`.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace irgs::comms {

enum class LinkScheme { kSerial, kTcp, kUdp };

struct LinkUrl {
  LinkScheme scheme = LinkScheme::kSerial;
  std::string device;  // serial device path
  std::string host;    // tcp/udp host, empty = any
  std::uint16_t port = 0;
  std::uint32_t baud = 57600;
  std::map<std::string, std::string> options;

  std::string toString() const;
};

struct LinkUrlResult {
  std::optional<LinkUrl> url;
  std::string error;  // set when url is empty
};

LinkUrlResult parseLinkUrl(const std::string& text);

// The baud of the serial line behind the link, which bounds its bytes per second (baud / 10):
// a serial URL's baud; for tcp/udp the `baud` option when given (a TCP bridge to a robot's
// UART, or a link model at that rate), else empty (unknown). parseLinkUrl rejects a `baud`
// option that is not a positive integer on any scheme.
std::optional<std::uint32_t> linkBaud(const LinkUrl& url);

}  // namespace irgs::comms
