#include "comms/transport/transport_factory.hpp"

#include "comms/transport/serial_transport.hpp"
#include "comms/transport/tcp_transport.hpp"
#include "comms/transport/udp_transport.hpp"

#include <charconv>
#include <optional>
#include <stdexcept>

namespace irgs::comms {
namespace {

// Option lookups return an error text on a bad value; `out` keeps its default when absent.
std::string boolOption(const LinkUrl& url, const std::string& key, bool& out) {
  const auto it = url.options.find(key);
  if (it == url.options.end())
    return {};
  const std::string& v = it->second;
  if (v.empty() || v == "1" || v == "true" || v == "yes" || v == "on") {
    out = true;
    return {};
  }
  if (v == "0" || v == "false" || v == "no" || v == "off") {
    out = false;
    return {};
  }
  return "option " + key + "='" + v + "' is not a boolean (use 1 or 0)";
}

template <typename T>
std::string numberOption(const LinkUrl& url, const std::string& key, T min_value, T& out) {
  const auto it = url.options.find(key);
  if (it == url.options.end())
    return {};
  const std::string& v = it->second;
  T value{};
  const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
  if (ec != std::errc{} || ptr != v.data() + v.size() || value < min_value)
    return "option " + key + "='" + v + "' is not a valid number (at least " +
           std::to_string(min_value) + ")";
  out = value;
  return {};
}

TransportResult failure(std::string error) {
  return {nullptr, std::move(error)};
}

}  // namespace

TransportResult makeTransport(const LinkUrl& url, IoThread& io, TransportCallbacks callbacks) {
  std::size_t txq = kDefaultTxQueueBytes;
  if (auto e = numberOption<std::size_t>(url, "txq", 64, txq); !e.empty())
    return failure(e);

  switch (url.scheme) {
    case LinkScheme::kSerial: {
      SerialOptions o;
      o.device = url.device;
      o.baud = url.baud;
      o.tx_queue_bytes = txq;
      if (const auto it = url.options.find("flow"); it != url.options.end()) {
        const std::string& v = it->second;
        if (v == "none" || v == "off" || v == "0")
          o.flow = FlowControl::kNone;
        else if (v == "rtscts" || v == "rts" || v == "hw" || v == "hardware" || v == "crtscts")
          o.flow = FlowControl::kHardware;
        else
          return failure("option flow='" + v + "' is unknown (use none or rtscts)");
      }
      if (auto e = boolOption(url, "exclusive", o.exclusive); !e.empty())
        return failure(e);
      return {makeSerialTransport(io, std::move(o), std::move(callbacks)), {}};
    }
    case LinkScheme::kTcp: {
      bool listen = false;
      if (auto e = boolOption(url, "listen", listen); !e.empty())
        return failure(e);
      if (listen) {
        TcpServerOptions o;
        o.host = url.host;
        o.port = url.port;
        o.tx_queue_bytes = txq;
        return {makeTcpServerTransport(io, std::move(o), std::move(callbacks)), {}};
      }
      TcpClientOptions o;
      o.host = url.host.empty() ? "127.0.0.1" : url.host;
      o.port = url.port;
      o.tx_queue_bytes = txq;
      long long timeout_ms = o.connect_timeout.count();
      if (auto e = numberOption<long long>(url, "timeout_ms", 1, timeout_ms); !e.empty())
        return failure(e);
      o.connect_timeout = std::chrono::milliseconds(timeout_ms);
      return {makeTcpClientTransport(io, std::move(o), std::move(callbacks)), {}};
    }
    case LinkScheme::kUdp: {
      UdpOptions o;
      o.host = url.host;
      o.port = url.port;
      o.tx_queue_bytes = txq;
      // No host, or every interface: listen (sending to 0.0.0.0 would mean nothing).
      o.listen = url.host.empty() || url.host == "0.0.0.0";
      if (auto e = boolOption(url, "listen", o.listen); !e.empty())
        return failure(e);
      if (!o.listen && o.host.empty())
        return failure("udp sender needs a host, e.g. udp://192.168.4.1:14555");
      if (auto e = numberOption<std::uint16_t>(url, "bind", 0, o.local_port); !e.empty())
        return failure(e);
      long long peer_timeout_ms = o.peers.udp_peer_timeout.count();
      if (auto e = numberOption<long long>(url, "peer_timeout_ms", 1, peer_timeout_ms); !e.empty())
        return failure(e);
      o.peers.udp_peer_timeout = std::chrono::milliseconds(peer_timeout_ms);
      return {makeUdpTransport(io, std::move(o), std::move(callbacks)), {}};
    }
  }
  return failure("unsupported link scheme");
}

std::unique_ptr<Transport> openTransport(const LinkUrl& url, IoThread& io,
                                         TransportCallbacks callbacks) {
  auto result = makeTransport(url, io, std::move(callbacks));
  if (!result.transport)
    throw std::invalid_argument(result.error);
  result.transport->open();
  return std::move(result.transport);
}

}  // namespace irgs::comms
