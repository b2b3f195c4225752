#pragma once
// UDP transport. Two roles, as in MAVLink tools:
//  * listener: bind a local port, remember the last peer that sent a datagram and reply to it
//    (a robot or mavlink-router sending to the ground station's 14550);
//  * sender: send to a configured host:port from an ephemeral (or given) local port; datagrams
//    from any sender are delivered, replies still go to the configured remote.
// Each send() is one datagram. A datagram the OS refuses (no route, ICMP unreachable) is counted
// as dropped; it does not fail the link, since UDP has no connection to lose.

#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport.hpp"

#include <memory>
#include <string>

namespace irgs::comms {

struct UdpOptions {
  bool listen = true;
  // listener: local address to bind (empty = all IPv4 interfaces) and port (0 = ephemeral).
  // sender: remote host (name or address) and port.
  std::string host;
  std::uint16_t port = 14550;
  std::uint16_t local_port = 0;  // sender only: local port to bind, 0 = ephemeral
  std::size_t tx_queue_bytes = kDefaultTxQueueBytes;
};

std::unique_ptr<Transport> makeUdpTransport(IoThread& io, UdpOptions options,
                                            TransportCallbacks callbacks = {});

}  // namespace irgs::comms
