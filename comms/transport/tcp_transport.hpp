#pragma once
// TCP transports: a client (to a robot's Wi-Fi bridge, a simulator, mavlink-router) and a server
// that serves one client at a time: while that client is active a second one is refused (its
// connection closed at once), never swapped in unannounced (PeerPolicy, transport.hpp).

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
  // Local address to bind. Empty = loopback (127.0.0.1): only programs on this computer can
  // connect. "0.0.0.0" = every IPv4 interface (a peer elsewhere on the network); or one
  // interface's address.
  std::string host;
  std::uint16_t port = 5760;  // 0 = ephemeral, read it back with Transport::localPort()
  std::size_t tx_queue_bytes = kDefaultTxQueueBytes;
  PeerPolicy peers;  // who is served when a second client connects
};

inline constexpr char kLoopbackAddress[] = "127.0.0.1";

// Client: open() resolves and connects; failure, timeout or the peer closing -> failed.
std::unique_ptr<Transport> makeTcpClientTransport(IoThread& io, TcpClientOptions options,
                                                  TransportCallbacks callbacks = {});

// Server: open() binds and listens (state opening, message "listening on ..."); a connected
// client makes it open; the client leaving returns it to opening (still listening). Only a
// failure to bind/listen/accept makes it failed. A client connecting while another one is
// active (options.peers) is refused: on_refused, the refusal bytes written, its connection
// closed, nothing it sends delivered. When the connected client is no longer active the
// newcomer replaces it (its queued bytes are discarded).
std::unique_ptr<Transport> makeTcpServerTransport(IoThread& io, TcpServerOptions options,
                                                  TransportCallbacks callbacks = {});

}  // namespace irgs::comms
