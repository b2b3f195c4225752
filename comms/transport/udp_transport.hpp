#pragma once
// UDP transport. Two roles, as in MAVLink tools:
//  * listener: bind a local port (loopback unless an address is given), take the first sender
//    as its peer and reply to it (a robot or mavlink-router sending to the ground station's
//    14550). While that peer is active (PeerPolicy: by default, it sent a datagram within
//    udp_peer_timeout) datagrams from any other sender are dropped and reported (on_refused),
//    so a second sender can neither inject into the stream nor take the replies over; once the
//    peer has gone silent the next sender becomes the peer;
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
  // listener: local address to bind (empty = loopback 127.0.0.1, "0.0.0.0" = every IPv4
  // interface) and port (0 = ephemeral).
  // sender: remote host (name or address) and port.
  std::string host;
  std::uint16_t port = 14550;
  std::uint16_t local_port = 0;  // sender only: local port to bind, 0 = ephemeral
  std::size_t tx_queue_bytes = kDefaultTxQueueBytes;
  PeerPolicy peers;  // listener: who is served when a second sender shows up
};

std::unique_ptr<Transport> makeUdpTransport(IoThread& io, UdpOptions options,
                                            TransportCallbacks callbacks = {});

}  // namespace irgs::comms
