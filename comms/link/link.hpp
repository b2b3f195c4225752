#pragma once
// One robot link on the shared IoThread: a Transport opened from a LinkUrl, the MAVLink decoder
// and encoder, a LinkSession (heartbeats, TIMESYNC, commands, statistics) and a periodic tick.
// It reopens the transport on its own after a failure (device node gone, connection refused,
// peer closed) or a heartbeat loss, every reconnect_initial_s doubling up to reconnect_max_s
// (1 s), until the peer's heartbeat is back or close() is called.
//
// Threading:
//  * Every public member may be called from any thread. open/close/send/sendCommand post to
//    the io thread and return at once; stats()/state() read a snapshot refreshed on every tick.
//  * All link state lives on the io thread. Callbacks (on_frame, on_event, command callbacks)
//    run on the io thread, never concurrently with each other; keep them short (they block every
//    link) and post to the GUI thread from there. An exception from a callback is caught and
//    counted (callbackExceptions()), the link keeps running.
//  * The destructor may run on any thread but not inside one of this link's own callbacks; when
//    it returns no callback runs any more. The IoThread must outlive the link.

#include "comms/link/command_manager.hpp"
#include "comms/link/frame_tap.hpp"
#include "comms/link/link_session.hpp"
#include "comms/link/link_types.hpp"
#include "comms/link/link_url.hpp"
#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/message_info.hpp"
#include "comms/mavlink/signing.hpp"
#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport_factory.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace irgs::comms {

struct LinkConfig {
  LinkSessionConfig session{};
  double tick_s = 0.05;               // session tick / reconnect check period
  double reconnect_initial_s = 0.25;  // first reopen delay after a failure
  double reconnect_max_s = 1.0;       // backoff cap
  // MAVLink 2 signing of everything we send and verification of what we receive.
  std::optional<mavlink::SigningKey> signing_key{};
  std::uint8_t signing_link_id = 0;
  bool require_signed = false;  // with a key: drop unsigned frames
  // Sees every received chunk and every sent frame (session recording); empty = none.
  FrameTap tap{};
  // Builds the transport instead of makeTransport(url) (replay from a recording, in-memory
  // tests); the URL then only names the link. Empty = makeTransport.
  std::function<TransportResult(IoThread& io, TransportCallbacks callbacks)> make_transport{};
};

struct LinkCallbacks {
  std::function<void(const mavlink::Frame& frame)> on_frame;  // every valid frame received
  std::function<void(const LinkEvent& event)> on_event;       // console events
};

class Link;

struct LinkResult {
  std::unique_ptr<Link> link;  // null when error is set
  std::string error;
};

class Link {
 public:
  // Builds the link (not opened yet). Bad URL options or config values are reported in error.
  static LinkResult create(IoThread& io, const LinkUrl& url, LinkConfig config = {},
                           LinkCallbacks callbacks = {});
  ~Link();
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  // Starts connecting (Disconnected -> Connecting); reconnects on its own from then on.
  void open();
  // Closes the transport, cancels pending commands (their callbacks report kCancelled).
  void close();

  // Encodes and sends one message with our system/component id. Lossy: dropped when the
  // transport is not open or its queue is full (as a radio would).
  template <class M>
  void send(const M& message) {
    RawMessage raw;
    raw.info = mavlink::messageInfoOf<M>();
    message.pack(std::span<std::uint8_t, M::kMaxLength>(raw.payload.data(), M::kMaxLength));
    sendRaw(raw);
  }
  // Runs the command protocol (retries, ack, timeout); `done` runs on the io thread.
  void sendCommand(const mavlink::CommandLong& command, CommandCallback done = {});

  LinkState state() const;
  LinkStats stats() const;
  std::string description() const;  // the transport's, e.g. "tcp client 127.0.0.1:5760"
  std::uint16_t localPort() const;  // TCP server / UDP bound port (0 = none yet)
  std::uint64_t callbackExceptions() const;

  struct Impl;  // io-thread state (link.cpp)

 private:
  struct RawMessage {
    mavlink::MessageInfo info{};
    std::array<std::uint8_t, mavlink::kMaxPayloadLength> payload{};
  };
  explicit Link(std::shared_ptr<Impl> impl);
  void sendRaw(const RawMessage& raw);

  std::shared_ptr<Impl> impl_;
};

}  // namespace irgs::comms
