#pragma once
// Transports from link URLs (see comms/link/link_url.hpp). Options understood here:
//   serial:  baud=N (parsed by LinkUrl), flow=none|rtscts (aliases: rts, hw, hardware),
//            exclusive=0|1
//   tcp:     listen=1 (server; host = local address to bind, empty = loopback 127.0.0.1,
//            0.0.0.0 = every interface; one client at a time, a second one is refused while
//            the first is connected), timeout_ms=N (client connect)
//   udp:     listen=1, or an empty host or 0.0.0.0 (listener: host = local address as for tcp; the
//   first
//            sender is the peer, others are refused while it sent within peer_timeout_ms=N,
//            default 3000); otherwise sender to host:port; bind=PORT (sender's local port)
//   all:     txq=BYTES (transmit queue bound)
// Other options are left for higher layers (the link manager) and ignored here.

#include "comms/link/link_url.hpp"
#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport.hpp"

#include <memory>
#include <string>

namespace irgs::comms {

struct TransportResult {
  std::unique_ptr<Transport> transport;  // null when error is set
  std::string error;
};

// Builds the transport (closed, not yet opened). Bad option values are reported, not thrown.
TransportResult makeTransport(const LinkUrl& url, IoThread& io, TransportCallbacks callbacks = {});

// makeTransport + open(). Throws std::invalid_argument with the diagnostic on a bad option value
// (validate user input with makeTransport first when it comes from a text field).
std::unique_ptr<Transport> openTransport(const LinkUrl& url, IoThread& io,
                                         TransportCallbacks callbacks = {});

}  // namespace irgs::comms
