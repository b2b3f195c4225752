#pragma once
// TCP transports: a client (to a robot's Wi-Fi bridge, a simulator, mavlink-router) and a server
// that accepts one client at a time (a new client replaces the old one).

#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport.hpp"

#include <chrono>
#include <memory>
#include <string>

namespace irgs::comms {

struct TcpClientOptions {
  std::string host = "127.0.0.1";  // name or address
  std::uint16_t port = 5760;
  std::chrono::milliseconds connect_timeout{3000};  // resolve + connect
  std::size_t tx_queue_bytes = kDefaultTxQueueBytes;
};

struct TcpServerOptions {
  std::string host;           // local address to bind; empty = all IPv4 interfaces
  std::uint16_t port = 5760;  // 0 = ephemeral, read it back with Transport::localPort()
  std::size_t tx_queue_bytes = kDefaultTxQueueBytes;
};

// Client: open() resolves and connects; failure, timeout or the peer closing -> failed.
std::unique_ptr<Transport> makeTcpClientTransport(IoThread& io, TcpClientOptions options,
                                                  TransportCallbacks callbacks = {});

// Server: open() binds and listens (state opening, message "listening on ..."); a connected
// client makes it open; the client leaving returns it to opening (still listening). Only a
// failure to bind/listen/accept makes it failed. Queued bytes are discarded when the client
// changes.
std::unique_ptr<Transport> makeTcpServerTransport(IoThread& io, TcpServerOptions options,
                                                  TransportCallbacks callbacks = {});

}  // namespace irgs::comms
