#include "comms/transport/udp_transport.hpp"

#include "comms/transport/transport_core.hpp"

#include <boost/asio/error.hpp>
#include <boost/asio/ip/udp.hpp>

#include <array>
#include <chrono>
#include <mutex>

namespace irgs::comms {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;

std::string endpointText(const udp::endpoint& ep) {
  return ep.address().to_string() + ":" + std::to_string(ep.port());
}

class UdpCore final : public detail::TransportCore {
 public:
  UdpCore(IoThread& io, UdpOptions options, TransportCallbacks callbacks)
      : TransportCore(io, options.tx_queue_bytes, describe(options), std::move(callbacks)),
        options_(std::move(options)) {}

 protected:
  void doOpen() override {
    {
      const std::lock_guard lock(peer_mutex_);
      has_destination_ = false;
    }
    if (options_.listen) {
      boost::system::error_code ec;
      const asio::ip::address address = asio::ip::make_address(listenHost(options_), ec);
      if (ec) {
        fail("udp: '" + options_.host + "' is not a local IP address");
        return;
      }
      bindAndStart(udp::endpoint(address, options_.port));
      return;
    }
    const auto gen = generation();
    resolver_.async_resolve(
        udp::v4(), options_.host, std::to_string(options_.port),
        [self = self<UdpCore>(), gen](const boost::system::error_code& ec,
                                      const udp::resolver::results_type& results) {
          if (!self->current(gen) || ec == asio::error::operation_aborted)
            return;
          if (ec || results.empty()) {
            self->fail("cannot resolve '" + self->options_.host +
                       "': " + (ec ? ec.message() : std::string("no IPv4 address")));
            return;
          }
          {
            const std::lock_guard lock(self->peer_mutex_);
            self->destination_ = results.begin()->endpoint();
          }
          self->bindAndStart(udp::endpoint(udp::v4(), self->options_.local_port));
        });
  }

  void doClose() override {
    resolver_.cancel();
    boost::system::error_code ignored;
    socket_.close(ignored);
  }

  bool readyToSend() const override {
    const std::lock_guard lock(peer_mutex_);
    return has_destination_;
  }

  void doWrite(std::uint64_t gen, TxQueue::Chunk chunk) override {
    udp::endpoint to;
    {
      const std::lock_guard lock(peer_mutex_);
      to = destination_;
    }
    const auto buffer = asio::buffer(*chunk);
    socket_.async_send_to(buffer, to,
                          [self = self<UdpCore>(), gen, chunk = std::move(chunk)](
                              const boost::system::error_code& ec, std::size_t n) {
                            if (ec && ec != asio::error::operation_aborted)
                              self->writeDropped(gen);  // datagram lost; the link lives on
                            else
                              self->writeDone(gen, ec, n);
                          });
  }

 private:
  static std::string listenHost(const UdpOptions& o) {
    return o.host.empty() ? std::string("127.0.0.1") : o.host;
  }

  static std::string describe(const UdpOptions& o) {
    if (o.listen)
      return "udp listener " + listenHost(o) + ":" + std::to_string(o.port);
    return "udp to " + o.host + ":" + std::to_string(o.port);
  }

  void bindAndStart(const udp::endpoint& local) {
    boost::system::error_code ec;
    socket_.open(local.protocol(), ec);
    if (!ec)
      socket_.bind(local, ec);
    if (ec) {
      fail("cannot bind udp " + endpointText(local) + ": " + ec.message());
      return;
    }
    const auto bound = socket_.local_endpoint(ec);
    setLocalPort(bound.port());
    std::string message = "bound udp " + endpointText(bound);
    if (!options_.listen) {
      const std::lock_guard lock(peer_mutex_);
      has_destination_ = true;
      message += ", sending to " + endpointText(destination_);
    }
    const auto gen = generation();
    setState(TransportState::kOpen, message);
    if (current(gen))
      startRead(gen);
  }

  void startRead(std::uint64_t gen) {
    socket_.async_receive_from(
        asio::buffer(rx_), sender_,
        [self = self<UdpCore>(), gen](const boost::system::error_code& ec, std::size_t n) {
          self->onRead(gen, ec, n);
        });
  }

  void onRead(std::uint64_t gen, const boost::system::error_code& ec, std::size_t n) {
    if (!current(gen) || ec == asio::error::operation_aborted)
      return;
    if (ec) {
      // ICMP errors surface here (connection_refused): not fatal for a datagram socket.
      startRead(gen);
      return;
    }
    if (options_.listen && !acceptSender()) {
      refused(endpointText(sender_));  // another sender while our peer is active: dropped
      startRead(gen);
      return;
    }
    deliver(std::span<const std::uint8_t>(rx_.data(), n));
    if (current(gen))
      startRead(gen);
  }

  // Listener: true when the datagram just received from sender_ is to be delivered (it is our
  // peer, or the first sender, or it replaces a peer that has gone silent); updates the peer.
  // The policy's callback runs without peer_mutex_ held (it may well call send()).
  bool acceptSender() {
    const auto now = std::chrono::steady_clock::now();
    bool newcomer = false;
    {
      const std::lock_guard lock(peer_mutex_);
      newcomer = has_destination_ && sender_ != destination_;
    }
    if (newcomer && peerActive(now))
      return false;
    {
      const std::lock_guard lock(peer_mutex_);
      destination_ = sender_;
      has_destination_ = true;
    }
    last_peer_datagram_ = now;
    return true;
  }

  bool peerActive(std::chrono::steady_clock::time_point now) const {
    if (options_.peers.peer_active)
      return options_.peers.peer_active();
    return now - last_peer_datagram_ < options_.peers.udp_peer_timeout;
  }

  UdpOptions options_;
  udp::socket socket_{io()};
  udp::resolver resolver_{io()};
  udp::endpoint sender_;
  std::array<std::uint8_t, 65536> rx_{};  // a whole datagram always fits

  mutable std::mutex peer_mutex_;  // send() reads has_destination_ from any thread
  udp::endpoint destination_;
  bool has_destination_ = false;
  std::chrono::steady_clock::time_point last_peer_datagram_{};  // io thread only
};

}  // namespace

std::unique_ptr<Transport> makeUdpTransport(IoThread& io, UdpOptions options,
                                            TransportCallbacks callbacks) {
  return std::make_unique<detail::AsioTransport>(
      std::make_shared<UdpCore>(io, std::move(options), std::move(callbacks)));
}

}  // namespace irgs::comms
