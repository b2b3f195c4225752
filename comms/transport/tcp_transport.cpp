#include "comms/transport/tcp_transport.hpp"

#include "comms/transport/transport_core.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>

#include <sys/socket.h>

#include <array>
#include <cerrno>
#include <vector>

namespace irgs::comms {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

std::string endpointText(const tcp::endpoint& ep) {
  return ep.address().to_string() + ":" + std::to_string(ep.port());
}

std::string readErrorText(const boost::system::error_code& ec) {
  if (ec == asio::error::eof)
    return "connection closed by peer";
  return ec.message();
}

// Shared by client and server: read loop and writes on one connected socket.
class TcpStreamCore : public detail::TransportCore {
 public:
  using TransportCore::TransportCore;

 protected:
  void doWrite(std::uint64_t gen, TxQueue::Chunk chunk) override {
    const auto buffer = asio::buffer(*chunk);
    asio::async_write(
        socket_, buffer,
        [self = self<TcpStreamCore>(), gen, chunk = std::move(chunk)](
            const boost::system::error_code& ec, std::size_t n) { self->writeDone(gen, ec, n); });
  }

  void startRead(std::uint64_t gen) {
    socket_.async_read_some(asio::buffer(rx_), [self = self<TcpStreamCore>(), gen](
                                                   const boost::system::error_code& ec,
                                                   std::size_t n) { self->onRead(gen, ec, n); });
  }

  void closeSocket() {
    boost::system::error_code ignored;
    socket_.shutdown(tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
  }

  void configureSocket() {
    boost::system::error_code ignored;
    socket_.set_option(tcp::no_delay(true), ignored);  // small control messages: no Nagle delay
  }

  // The connection ended (error or EOF); `gen` is current.
  virtual void onConnectionLost(const std::string& reason) = 0;

  tcp::socket socket_{io()};

 private:
  void onRead(std::uint64_t gen, const boost::system::error_code& ec, std::size_t n) {
    if (!current(gen) || ec == asio::error::operation_aborted)
      return;
    if (ec) {
      onConnectionLost(readErrorText(ec));
      return;
    }
    deliver(std::span<const std::uint8_t>(rx_.data(), n));
    if (current(gen))
      startRead(gen);
  }

  std::array<std::uint8_t, 4096> rx_{};
};

class TcpClientCore final : public TcpStreamCore {
 public:
  TcpClientCore(IoThread& io, TcpClientOptions options, TransportCallbacks callbacks)
      : TcpStreamCore(io, options.tx_queue_bytes,
                      "tcp client " + options.host + ":" + std::to_string(options.port),
                      std::move(callbacks)),
        options_(std::move(options)) {}

 protected:
  void doOpen() override {
    const auto gen = generation();
    timer_.expires_after(options_.connect_timeout);
    timer_.async_wait([self = self<TcpClientCore>(), gen](const boost::system::error_code& ec) {
      if (ec || !self->current(gen) || self->state() != TransportState::kOpening)
        return;
      self->fail("connecting to " + self->target() + " timed out after " +
                 std::to_string(self->options_.connect_timeout.count()) + " ms");
    });
    resolver_.async_resolve(
        options_.host, std::to_string(options_.port),
        [self = self<TcpClientCore>(), gen](const boost::system::error_code& ec,
                                            const tcp::resolver::results_type& results) {
          self->onResolved(gen, ec, results);
        });
  }

  void doClose() override {
    timer_.cancel();
    resolver_.cancel();
    closeSocket();
  }

  void onConnectionLost(const std::string& reason) override {
    fail("tcp connection to " + target() + " lost: " + reason);
  }

 private:
  std::string target() const { return options_.host + ":" + std::to_string(options_.port); }

  void onResolved(std::uint64_t gen, const boost::system::error_code& ec,
                  const tcp::resolver::results_type& results) {
    if (!current(gen) || ec == asio::error::operation_aborted)
      return;
    if (ec) {
      fail("cannot resolve '" + options_.host + "': " + ec.message());
      return;
    }
    asio::async_connect(socket_, results,
                        [self = self<TcpClientCore>(), gen](const boost::system::error_code& cec,
                                                            const tcp::endpoint& ep) {
                          self->onConnected(gen, cec, ep);
                        });
  }

  void onConnected(std::uint64_t gen, const boost::system::error_code& ec,
                   const tcp::endpoint& ep) {
    if (!current(gen) || ec == asio::error::operation_aborted)
      return;
    if (ec) {
      fail("cannot connect to " + target() + ": " + ec.message());
      return;
    }
    timer_.cancel();
    configureSocket();
    boost::system::error_code ignored;
    setLocalPort(socket_.local_endpoint(ignored).port());
    setState(TransportState::kOpen, "connected to " + endpointText(ep));
    if (current(gen))
      startRead(gen);
  }

  TcpClientOptions options_;
  tcp::resolver resolver_{io()};
  asio::steady_timer timer_{io()};
};

// A client the server turned away: the refusal bytes are written, our sending side is shut down,
// and whatever the client still sends is read and discarded until it closes or kRefusalLinger
// passes. Closing with unread input would reset the connection, which can discard the refusal
// before the client reads it. Holds no reference to the server: it lives on its own handlers.
class RefusedConnection : public std::enable_shared_from_this<RefusedConnection> {
 public:
  static constexpr std::chrono::milliseconds kRefusalLinger{250};

  RefusedConnection(tcp::socket socket, std::vector<std::uint8_t> bytes)
      : socket_(std::move(socket)), timer_(socket_.get_executor()), bytes_(std::move(bytes)) {}

  void start() {
    timer_.expires_after(kRefusalLinger);
    timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec != asio::error::operation_aborted)
        self->finish();
    });
    asio::async_write(
        socket_, asio::buffer(bytes_),
        [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
          if (ec) {
            self->finish();
            return;
          }
          boost::system::error_code ignored;
          self->socket_.shutdown(tcp::socket::shutdown_send, ignored);
          self->drain();
        });
  }

 private:
  void drain() {
    socket_.async_read_some(
        asio::buffer(sink_),
        [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
          if (ec)
            self->finish();
          else
            self->drain();
        });
  }
  void finish() {
    timer_.cancel();
    boost::system::error_code ignored;
    socket_.close(ignored);
  }

  tcp::socket socket_;
  asio::steady_timer timer_;
  std::vector<std::uint8_t> bytes_;
  std::array<std::uint8_t, 512> sink_{};
};

class TcpServerCore final : public TcpStreamCore {
 public:
  TcpServerCore(IoThread& io, TcpServerOptions options, TransportCallbacks callbacks)
      : TcpStreamCore(io, options.tx_queue_bytes,
                      "tcp server " + bindHost(options) + ":" + std::to_string(options.port),
                      std::move(callbacks)),
        options_(std::move(options)) {}

 protected:
  void doOpen() override {
    boost::system::error_code ec;
    const asio::ip::address address = asio::ip::make_address(bindHost(options_), ec);
    if (ec) {
      fail("tcp server: '" + options_.host + "' is not a local IP address");
      return;
    }
    const tcp::endpoint endpoint(address, options_.port);
    acceptor_.open(endpoint.protocol(), ec);
    if (!ec)
      acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec)
      acceptor_.bind(endpoint, ec);
    if (!ec)
      acceptor_.listen(asio::socket_base::max_listen_connections, ec);
    if (ec) {
      fail("cannot listen on " + endpointText(endpoint) + ": " + ec.message());
      return;
    }
    const auto bound = acceptor_.local_endpoint(ec);
    setLocalPort(bound.port());
    listening_ = endpointText(bound);
    ++accept_session_;
    setState(TransportState::kOpening, "listening on " + listening_);
    startAccept(accept_session_);
  }

  void doClose() override {
    ++accept_session_;
    boost::system::error_code ignored;
    acceptor_.close(ignored);
    closeSocket();
  }

  void onConnectionLost(const std::string& reason) override {
    closeSocket();
    newGeneration();
    setState(TransportState::kOpening,
             "client " + client_ + " left (" + reason + "); listening on " + listening_);
  }

 private:
  static std::string bindHost(const TcpServerOptions& options) {
    return options.host.empty() ? std::string(kLoopbackAddress) : options.host;
  }

  void startAccept(std::uint64_t session) {
    acceptor_.async_accept([self = self<TcpServerCore>(), session](
                               const boost::system::error_code& ec, tcp::socket socket) {
      self->onAccepted(session, ec, std::move(socket));
    });
  }

  void onAccepted(std::uint64_t session, const boost::system::error_code& ec, tcp::socket socket) {
    if (session != accept_session_ || ec == asio::error::operation_aborted)
      return;
    if (ec) {
      // Transient per-connection errors (the client reset before we accepted it) are not fatal.
      if (ec == asio::error::connection_aborted || ec == asio::error::connection_reset) {
        startAccept(session);
        return;
      }
      fail("accept failed on " + listening_ + ": " + ec.message());
      return;
    }
    if (socket_.is_open() && peerHasClosed()) {
      // A client reconnecting: its FIN and the new SYN arrive together, and the accept may
      // complete before the read that would see the FIN. It has left; do not refuse its return.
      onConnectionLost("connection closed by peer");
    }
    const bool replacing = socket_.is_open();
    if (replacing && clientActive()) {
      refuse(std::move(socket));
      startAccept(session);
      return;
    }
    const std::string previous = client_;
    closeSocket();
    newGeneration();  // the previous client's reads, writes and queued bytes are void
    socket_ = std::move(socket);
    configureSocket();
    boost::system::error_code ignored;
    client_ = endpointText(socket_.remote_endpoint(ignored));
    const auto gen = generation();
    setState(TransportState::kOpen,
             "client " + client_ + " connected" +
                 (replacing ? " (replaced " + previous + ", which had gone silent)" : ""));
    if (current(gen))
      startRead(gen);
    if (session == accept_session_)
      startAccept(session);
  }

  // True when the connected client has closed its side and nothing it sent is left unread (a
  // peek at the socket, which never blocks).
  bool peerHasClosed() {
    std::uint8_t byte = 0;
    const ssize_t n = ::recv(socket_.native_handle(), &byte, 1, MSG_PEEK | MSG_DONTWAIT);
    return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
  }

  bool clientActive() const { return !options_.peers.peer_active || options_.peers.peer_active(); }

  void refuse(tcp::socket socket) {
    boost::system::error_code ignored;
    const std::string peer = endpointText(socket.remote_endpoint(ignored));
    refused(peer);
    std::vector<std::uint8_t> bytes;
    if (options_.peers.refusal_bytes)
      bytes = options_.peers.refusal_bytes(peer);
    std::make_shared<RefusedConnection>(std::move(socket), std::move(bytes))->start();
  }

  TcpServerOptions options_;
  tcp::acceptor acceptor_{io()};
  std::uint64_t accept_session_ = 0;
  std::string listening_;
  std::string client_;
};

}  // namespace

std::unique_ptr<Transport> makeTcpClientTransport(IoThread& io, TcpClientOptions options,
                                                  TransportCallbacks callbacks) {
  return std::make_unique<detail::AsioTransport>(
      std::make_shared<TcpClientCore>(io, std::move(options), std::move(callbacks)));
}

std::unique_ptr<Transport> makeTcpServerTransport(IoThread& io, TcpServerOptions options,
                                                  TransportCallbacks callbacks) {
  return std::make_unique<detail::AsioTransport>(
      std::make_shared<TcpServerCore>(io, std::move(options), std::move(callbacks)));
}

}  // namespace irgs::comms
