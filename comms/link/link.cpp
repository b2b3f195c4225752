#include "comms/link/link.hpp"

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/transport/transport_factory.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <mutex>
#include <stdexcept>
#include <variant>
#include <vector>

namespace irgs::comms {

namespace mav = mavlink;

struct Link::Impl : std::enable_shared_from_this<Link::Impl> {
  Impl(IoThread& io_thread, LinkConfig link_config, LinkCallbacks link_callbacks)
      : io(io_thread),
        config(std::move(link_config)),
        callbacks(std::move(link_callbacks)),
        decoder(mav::DecoderConfig{.signing_key = config.signing_key,
                                   .require_signed = config.require_signed}),
        encoder(config.session.system_id, config.session.component_id),
        session(config.session),
        timer(io_thread.context()),
        epoch(std::chrono::steady_clock::now()),
        backoff_s(config.reconnect_initial_s) {
    if (config.signing_key)
      encoder.enableSigning(*config.signing_key, config.signing_link_id);
  }

  // ---- io thread only below, except where noted ----
  double now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch).count();
  }

  void arm() {
    if (stopped)
      return;
    timer.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(config.tick_s)));
    timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec || self->stopped)
        return;
      self->onTick();
      self->arm();
    });
  }

  void onTick() {
    const double t = now();
    session.tick(t);
    if (started) {
      if (transport_state == TransportState::kFailed && t >= reopen_at_s) {
        reopen(t, last_transport_message.empty() ? "transport failed" : last_transport_message);
      } else if (session.state() == LinkState::kLost && transport_state == TransportState::kOpen &&
                 t - opened_at_s >= std::max(config.session.timeout_s, backoff_s)) {
        // Open but silent (a dead radio, a hung peer): start over from the device.
        reopen(t, "no heartbeat");
      }
    }
    flush(t);
  }

  void reopen(double t, const std::string& reason) {
    session.onReconnecting(t, reason);
    decoder.reset();
    transport_state = TransportState::kOpening;
    opened_at_s = t;  // counts as an attempt even if it fails at once
    reopen_at_s = t + backoff_s;
    backoff_s = std::min(backoff_s * 2.0, config.reconnect_max_s);
    transport->open();  // restarts the connection when still open
  }

  void onBytes(std::span<const std::uint8_t> bytes) {
    // Closed: the transport closes on a handler of its own after close()'s, so a read that
    // completes in between would be tapped and decoded after the owner took its last data
    // (LinkedRobot::finish) — a recording would then hold bytes the live session never used
    // (a re-run found one sample more than the live map had, on a loaded machine).
    if (stopped || !started)
      return;
    const double t = now();
    if (config.tap)
      guarded(
          [&] { config.tap(TapDirection::kReceived, std::chrono::steady_clock::now(), bytes); });
    frames.clear();
    const auto counters = decoder.feed(bytes, frames);
    session.onReceived(bytes.size(), counters, t);
    for (const auto& frame : frames) {
      session.onFrame(frame, t);
      // An event a frame caused (link up on the first heartbeat) reaches the owner before the
      // frames after it: what the owner does on it (a robot resets its sample assembly) then
      // happens at one place in the byte stream, however the bytes were split into reads.
      if (session.hasPendingEvents()) {
        flush(t);
        if (stopped)
          return;
      }
      if (callbacks.on_frame)
        guarded([&] { callbacks.on_frame(frame); });
      if (stopped)
        return;
    }
    flush(t);
  }

  // A listening transport turned a second robot away (the first one keeps the link). One
  // console line per new peer, else at most one per kRefusalReport_s: a UDP sender is refused
  // datagram by datagram.
  void onRefused(const std::string& peer) {
    if (stopped)
      return;
    const double t = now();
    ++refused_total;
    if (peer == last_refused_peer && t < next_refusal_report_s)
      return;
    last_refused_peer = peer;
    next_refusal_report_s = t + kRefusalReport_s;
    session.onTransportStatus(t, "refused " + peer + ": another peer has the link (" +
                                     std::to_string(refused_total) + " refused)");
    flush(t);
  }

  void onTransportState(TransportState new_state, const std::string& message) {
    if (stopped)
      return;
    const double t = now();
    const TransportState previous = transport_state;
    transport_state = new_state;
    if (!message.empty())
      last_transport_message = message;
    switch (new_state) {
      case TransportState::kOpen:
        decoder.reset();
        opened_at_s = t;
        session.onTransportOpen(t, message.empty() ? transport->description() : message);
        break;
      case TransportState::kOpening:
        if (previous == TransportState::kOpen)  // a TCP server whose client left
          session.onTransportDown(t, message.empty() ? "peer disconnected" : message);
        else
          session.onTransportStatus(t, message);
        break;
      case TransportState::kFailed:
        session.onTransportDown(t, message.empty() ? "transport failed" : message);
        reopen_at_s = std::max(reopen_at_s, t + config.reconnect_initial_s);
        break;
      case TransportState::kClosed:
        break;
    }
    flush(t);
  }

  void flush(double t) {
    auto out = session.takeOutput();
    for (const auto& message : out.messages)
      std::visit([&](const auto& m) { transmit(encoder.encode(m, signingTime()), t); }, message);
    for (const auto& event : out.events) {
      if (event.kind == LinkEventKind::kLinkUp)
        backoff_s = config.reconnect_initial_s;
      if (callbacks.on_event)
        guarded([&] { callbacks.on_event(event); });
      if (stopped)
        return;
    }
    for (auto& done : out.completed) {
      if (done.callback)
        guarded([&] { done.callback(done.result); });
      if (stopped)
        return;
    }
    publish(t);
  }

  void transmit(const mav::EncodedFrame& frame, double t) {
    if (transport && transport->send(frame.view())) {
      session.onSent(frame.size, t);
      if (config.tap)
        guarded([&] {
          config.tap(TapDirection::kSent, std::chrono::steady_clock::now(), frame.view());
        });
    }
  }

  std::uint64_t signingTime() const {
    return config.signing_key ? mav::signingTimestampAt(std::chrono::system_clock::now()) : 0;
  }

  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (...) {
      callback_exceptions.fetch_add(1);
    }
  }

  void publish(double t) {
    const auto s = session.stats(t);
    state.store(s.state);
    const std::lock_guard lock(snapshot_mutex);
    snapshot = s;
  }

  void shutdownNow() {
    stopped = true;
    timer.cancel();
    transport.reset();  // no transport callback after this
    callbacks = {};
  }

  IoThread& io;
  LinkConfig config;
  LinkCallbacks callbacks;
  std::unique_ptr<Transport> transport;
  mav::FrameDecoder decoder;
  mav::FrameEncoder encoder;
  LinkSession session;
  boost::asio::steady_timer timer;
  std::chrono::steady_clock::time_point epoch;
  std::vector<mav::Frame> frames;

  bool started = false;
  bool stopped = false;
  TransportState transport_state = TransportState::kClosed;  // as last reported
  std::string last_transport_message;
  double opened_at_s = 0.0;
  double reopen_at_s = 0.0;
  double backoff_s;
  static constexpr double kRefusalReport_s = 5.0;
  std::uint64_t refused_total = 0;
  std::string last_refused_peer;
  double next_refusal_report_s = 0.0;

  // Any thread.
  std::atomic<LinkState> state{LinkState::kDisconnected};
  std::atomic<std::uint64_t> callback_exceptions{0};
  mutable std::mutex snapshot_mutex;
  LinkStats snapshot;
};

namespace {

bool positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

}  // namespace

LinkResult Link::create(IoThread& io, const LinkUrl& url, LinkConfig config,
                        LinkCallbacks callbacks) {
  if (!positive(config.tick_s) || !positive(config.reconnect_initial_s) ||
      !positive(config.reconnect_max_s) || config.reconnect_max_s < config.reconnect_initial_s)
    return {nullptr,
            "link config: tick_s and reconnect delays must be > 0, reconnect_max_s >= "
            "reconnect_initial_s"};
  std::shared_ptr<Impl> impl;
  try {
    impl = std::make_shared<Impl>(io, std::move(config), std::move(callbacks));
  } catch (const std::invalid_argument& e) {
    return {nullptr, std::string("link config: ") + e.what()};
  }
  // The transport's callbacks may hold a raw pointer: Impl destroys the transport (which then
  // never calls back again) before it goes away.
  TransportCallbacks tc;
  Impl* raw = impl.get();
  tc.on_bytes = [raw](std::span<const std::uint8_t> bytes) { raw->onBytes(bytes); };
  tc.on_state = [raw](TransportState state, const std::string& message) {
    raw->onTransportState(state, message);
  };
  tc.on_refused = [raw](const std::string& peer) { raw->onRefused(peer); };
  auto made = impl->config.make_transport ? impl->config.make_transport(io, std::move(tc))
                                          : makeTransport(url, io, std::move(tc));
  if (!made.transport)
    return {nullptr, made.error};
  impl->transport = std::move(made.transport);
  boost::asio::post(io.context(), [impl] { impl->arm(); });
  return {std::unique_ptr<Link>(new Link(std::move(impl))), {}};
}

Link::Link(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

Link::~Link() {
  auto& io = impl_->io;
  if (io.isCurrentThread() || !io.running()) {
    impl_->shutdownNow();
    return;
  }
  std::promise<void> done;
  boost::asio::post(io.context(), [&done, impl = impl_] {
    impl->shutdownNow();
    done.set_value();
  });
  done.get_future().wait();
}

void Link::open() {
  boost::asio::post(impl_->io.context(), [impl = impl_] {
    if (impl->stopped || impl->started)
      return;
    const double t = impl->now();
    impl->started = true;
    impl->backoff_s = impl->config.reconnect_initial_s;
    impl->session.start(t);
    impl->decoder.reset();
    impl->transport_state = TransportState::kOpening;
    impl->opened_at_s = t;
    impl->transport->open();
    impl->flush(t);
  });
}

void Link::close() {
  boost::asio::post(impl_->io.context(), [impl = impl_] {
    if (impl->stopped || !impl->started)
      return;
    const double t = impl->now();
    impl->started = false;
    impl->transport->close();
    impl->transport_state = TransportState::kClosed;
    impl->session.close(t);
    impl->flush(t);
  });
}

void Link::sendRaw(const RawMessage& raw) {
  boost::asio::post(impl_->io.context(), [impl = impl_, raw] {
    if (impl->stopped)
      return;
    impl->transmit(
        impl->encoder.encodePayload(
            raw.info, std::span<const std::uint8_t>(raw.payload.data(), raw.info.max_length),
            impl->signingTime()),
        impl->now());
  });
}

void Link::sendCommand(const mav::CommandLong& command, CommandCallback done) {
  boost::asio::post(impl_->io.context(), [impl = impl_, command, done = std::move(done)]() mutable {
    if (impl->stopped)
      return;
    const double t = impl->now();
    impl->session.sendCommand(command, std::move(done), t);
    impl->flush(t);
  });
}

LinkState Link::state() const {
  return impl_->state.load();
}

LinkStats Link::stats() const {
  const std::lock_guard lock(impl_->snapshot_mutex);
  return impl_->snapshot;
}

// impl_->transport is only reset by the destructor, so it is valid for the Link's lifetime;
// Transport::description/localPort are thread-safe.
std::string Link::description() const {
  return impl_->transport->description();
}

std::uint16_t Link::localPort() const {
  return impl_->transport->localPort();
}

std::uint64_t Link::callbackExceptions() const {
  return impl_->callback_exceptions.load();
}

}  // namespace irgs::comms
