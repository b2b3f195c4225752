#pragma once
// The byte-carrying link under a protocol: a serial port (also Bluetooth SPP /dev/rfcommN), a TCP
// client or server, or a UDP socket. Transports know nothing about framing; they move bytes and
// report their state. Modelled on libmavconn with the framing taken out.
//
// Threading contract:
//  * open(), close(), send(), state(), stats() may be called from any thread.
//  * Every callback is invoked on the IoThread that owns the transport (never concurrently with
//    another callback of the same IoThread). Keep callbacks short: they block all links.
//  * After the transport's destructor returns, none of its callbacks runs again. The destructor
//    may run on any thread, including the io thread (also from inside the transport's own
//    callback).
//  * The IoThread must outlive every transport created on it.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace irgs::comms {

// closed --open()--> opening --> open --(error / device lost / peer closed)--> failed
// Any state --close()--> closed. A TCP server stays `opening` (listening) until a client connects
// and returns to `opening` when its client leaves; reconnection after `failed` is the caller's
// job (call open() again).
enum class TransportState { kClosed, kOpening, kOpen, kFailed };

std::string_view toString(TransportState state);

struct TransportStats {
  std::uint64_t rx_bytes = 0;          // bytes delivered to on_bytes
  std::uint64_t tx_bytes = 0;          // bytes the OS accepted
  std::uint64_t tx_dropped_bytes = 0;  // refused by send() (queue full, not open, no UDP peer)
                                       // or discarded from the queue by close/failure
  std::size_t tx_queued_bytes = 0;     // waiting or in flight right now
  std::uint64_t refused_peers = 0;     // listeners: peers turned away (see on_refused)
};

struct TransportCallbacks {
  // Received bytes; the span is valid only during the call.
  std::function<void(std::span<const std::uint8_t> bytes)> on_bytes;
  // State change, or a new status message in the same state (e.g. "listening on :5760").
  std::function<void(TransportState state, const std::string& message)> on_state;
  // A listening transport turned a peer away because another one is attached: a second TCP
  // client (connection closed at once), a datagram from a second UDP sender (dropped). `peer`
  // is "address:port". Counted in TransportStats::refused_peers. Optional.
  std::function<void(const std::string& peer)> on_refused;
};

// Who a listening transport (TCP server, UDP listener) serves: the attached peer keeps the
// link while it is active, and a newcomer meanwhile is refused, never silently swapped in.
// `peer_active` is asked on the io thread when another peer shows up while one is attached:
// true keeps the attached peer (the newcomer is refused), false lets the newcomer replace it
// (the attached peer has gone silent). When empty, the transport decides: a connected TCP client
// stays active until it disconnects; a UDP peer stays active while it has sent a datagram within
// `udp_peer_timeout`.
struct PeerPolicy {
  std::function<bool()> peer_active;
  std::chrono::milliseconds udp_peer_timeout{3000};
  // Bytes written to a refused TCP client before its connection is closed (a protocol's "busy"
  // message, e.g. a MAVLink STATUSTEXT); argument: the refused peer. Empty: none.
  std::function<std::vector<std::uint8_t>(const std::string& peer)> refusal_bytes;
};

// Default bound of the transmit queue. At 115200 baud this is ~1.4 s of traffic; a queue that
// holds more only delays commands that are already stale.
inline constexpr std::size_t kDefaultTxQueueBytes = 16 * 1024;

class Transport {
 public:
  virtual ~Transport() = default;
  Transport() = default;
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;

  // Asynchronous: the state moves to opening and then open or failed through on_state.
  // Calling open() while opening/open restarts the connection.
  virtual void open() = 0;
  // Asynchronous: releases the device/socket, discards queued bytes, state -> closed.
  virtual void close() = 0;
  // Queues a copy of `bytes` for transmission (one write in flight, FIFO order). Returns false
  // and counts the bytes as dropped when the transport is not open or the queue bound would be
  // exceeded; never blocks. For UDP each call is one datagram.
  virtual bool send(std::span<const std::uint8_t> bytes) = 0;

  virtual TransportState state() const = 0;
  virtual TransportStats stats() const = 0;
  // Human-readable endpoint, e.g. "serial /dev/ttyUSB0 @115200" or "tcp client 10.0.0.2:5760".
  virtual std::string description() const = 0;
  // Local port bound by a TCP server or UDP socket (useful when asking for port 0), 0 otherwise
  // or before it is bound.
  virtual std::uint16_t localPort() const = 0;
};

}  // namespace irgs::comms
