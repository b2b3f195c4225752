// irgs-linkem: a TCP relay that behaves like a slow, late, lossy serial link (comms/link/
// link_model.hpp) between a ground station and a robot: latency and jitter, the byte rate of a
// UART at its baud, periodic stalls, byte loss and bit flips, each direction with its own
// seeded model, on the wall clock. One client at a time; the robot connection is opened when
// the client connects and closed with it.
//
//   irgs-linkem --listen 127.0.0.1:5770 --connect 127.0.0.1:5760 --delay-ms 150
//       --jitter-ms 100 --baud 115200 [--stall-every-s 20 --stall-ms 500] [--loss 1e-4]
//       [--corrupt 1e-4] [--seed 1]
//
// Prints one line per connection and, at the end of each, the bytes relayed, lost and flipped.
// A pty robot (irgs-robot --link PATH) is bridged with socat (docs/protocol.md, "Link model").

#include <utility>  // before Asio (Boost 1.74 under C++20)

#include <array>
#include <boost/asio.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "comms/link/link_model.hpp"

namespace asio = boost::asio;
using asio::ip::tcp;
using irgs::comms::LinkModel;
using irgs::comms::LinkModelConfig;

namespace {

struct Options {
  tcp::endpoint listen;
  tcp::endpoint connect;
  LinkModelConfig model;
};

void usage(std::FILE* out) {
  std::fputs(
      "usage: irgs-linkem --listen HOST:PORT --connect HOST:PORT [--delay-ms MS] [--jitter-ms MS]\n"
      "                   [--baud BAUD] [--stall-every-s S --stall-ms MS] [--loss P]\n"
      "                   [--corrupt P] [--seed N]\n"
      "A TCP relay behaving like a slow, late, lossy serial link in both directions.\n"
      "--listen port 0 takes any free port; the line 'linkem: listening on HOST:PORT' names it.\n",
      out);
}

std::optional<tcp::endpoint> endpoint(const std::string& text, bool any_port) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos)
    return std::nullopt;
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(text.substr(0, colon), ec);
  if (ec)
    return std::nullopt;
  try {
    const int port = std::stoi(text.substr(colon + 1));
    if (port < (any_port ? 0 : 1) || port > 65535)
      return std::nullopt;
    return tcp::endpoint(address, static_cast<unsigned short>(port));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<Options> parse(int argc, char** argv, std::string& error) {
  Options o;
  bool have_listen = false, have_connect = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      usage(stdout);
      std::exit(0);
    }
    if (i + 1 >= argc) {
      error = "option " + arg + " needs a value";
      return std::nullopt;
    }
    const std::string value = argv[++i];
    try {
      if (arg == "--listen" || arg == "--connect") {
        const auto e = endpoint(value, arg == "--listen");  // listen on port 0: any free one
        if (!e) {
          error = arg + ": expected HOST:PORT with a numeric address, got '" + value + "'";
          return std::nullopt;
        }
        (arg == "--listen" ? o.listen : o.connect) = *e;
        (arg == "--listen" ? have_listen : have_connect) = true;
      } else if (arg == "--delay-ms") {
        o.model.delay_s = std::stod(value) / 1000.0;
      } else if (arg == "--jitter-ms") {
        o.model.jitter_s = std::stod(value) / 1000.0;
      } else if (arg == "--baud") {
        o.model.baud = std::stod(value);
      } else if (arg == "--stall-every-s") {
        o.model.stall_every_s = std::stod(value);
      } else if (arg == "--stall-ms") {
        o.model.stall_s = std::stod(value) / 1000.0;
      } else if (arg == "--loss") {
        o.model.loss = std::stod(value);
      } else if (arg == "--corrupt") {
        o.model.corruption = std::stod(value);
      } else if (arg == "--seed") {
        o.model.seed = std::stoull(value);
      } else {
        error = "unknown option " + arg;
        return std::nullopt;
      }
    } catch (const std::exception&) {
      error = arg + ": not a number: '" + value + "'";
      return std::nullopt;
    }
  }
  if (!have_listen || !have_connect) {
    error = "--listen and --connect are required";
    return std::nullopt;
  }
  if (const auto e = irgs::comms::linkModelConfigError(o.model)) {
    error = *e;
    return std::nullopt;
  }
  return o;
}

// One relayed connection: client <-> robot, each direction through its own link model.
class Relay : public std::enable_shared_from_this<Relay> {
 public:
  Relay(const asio::any_io_executor& io, tcp::socket client, const Options& options, int number)
      : client_(std::move(client)),
        robot_(io),
        timer_(io),
        up_(seeded(options.model, 2 * number)),
        down_(seeded(options.model, 2 * number + 1)),
        number_(number),
        start_(std::chrono::steady_clock::now()) {}

  void start(const tcp::endpoint& robot) {
    auto self = shared_from_this();
    robot_.async_connect(robot, [self](const boost::system::error_code& ec) {
      if (ec) {
        std::printf("linkem: connection %d: robot unreachable: %s\n", self->number_,
                    ec.message().c_str());
        std::fflush(stdout);
        self->close();
        return;
      }
      self->read(self->client_, self->up_, self->client_buffer_);
      self->read(self->robot_, self->down_, self->robot_buffer_);
      self->tick();
    });
  }

 private:
  static LinkModelConfig seeded(LinkModelConfig c, int salt) {
    c.seed = c.seed * 1000003ULL + static_cast<unsigned>(salt);
    return c;
  }
  double now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void read(tcp::socket& from, LinkModel& into, std::array<std::uint8_t, 4096>& buffer) {
    auto self = shared_from_this();
    from.async_read_some(
        asio::buffer(buffer),
        [self, &from, &into, &buffer](const boost::system::error_code& ec, std::size_t n) {
          if (ec) {
            self->close();
            return;
          }
          into.send({buffer.data(), n}, self->now());
          self->read(from, into, buffer);
        });
  }
  void deliver(LinkModel& model, tcp::socket& to) {
    const std::vector<std::uint8_t> bytes = model.receive(now());
    boost::system::error_code ec;
    if (!bytes.empty())
      asio::write(to, asio::buffer(bytes), ec);
    if (ec)
      close();
  }
  void tick() {
    if (closed_)
      return;
    deliver(up_, robot_);
    deliver(down_, client_);
    timer_.expires_after(std::chrono::milliseconds(1));
    auto self = shared_from_this();
    timer_.async_wait([self](const boost::system::error_code& ec) {
      if (!ec)
        self->tick();
    });
  }
  void close() {
    if (closed_)
      return;
    closed_ = true;
    boost::system::error_code ignored;
    client_.close(ignored);
    robot_.close(ignored);
    timer_.cancel();
    std::printf(
        "linkem: connection %d closed: to robot %llu bytes (%llu lost, %llu flipped), to ground "
        "station %llu bytes (%llu lost, %llu flipped)\n",
        number_, static_cast<unsigned long long>(up_.stats().bytes_out),
        static_cast<unsigned long long>(up_.stats().lost),
        static_cast<unsigned long long>(up_.stats().corrupted),
        static_cast<unsigned long long>(down_.stats().bytes_out),
        static_cast<unsigned long long>(down_.stats().lost),
        static_cast<unsigned long long>(down_.stats().corrupted));
    std::fflush(stdout);
  }

  tcp::socket client_;
  tcp::socket robot_;
  asio::steady_timer timer_;
  LinkModel up_;    // ground station -> robot
  LinkModel down_;  // robot -> ground station
  std::array<std::uint8_t, 4096> client_buffer_{};
  std::array<std::uint8_t, 4096> robot_buffer_{};
  int number_;
  std::chrono::steady_clock::time_point start_;
  bool closed_ = false;
};

void accept(tcp::acceptor& acceptor, const Options& options, int& connections) {
  acceptor.async_accept([&](const boost::system::error_code& ec, tcp::socket client) {
    if (!ec) {
      const int n = ++connections;
      std::printf("linkem: connection %d from %s\n", n,
                  client.remote_endpoint().address().to_string().c_str());
      std::fflush(stdout);
      std::make_shared<Relay>(acceptor.get_executor(), std::move(client), options, n)
          ->start(options.connect);
    }
    accept(acceptor, options, connections);
  });
}

}  // namespace

int main(int argc, char** argv) {
  std::string error;
  const std::optional<Options> options = parse(argc, argv, error);
  if (!options) {
    std::fprintf(stderr, "irgs-linkem: %s\n", error.c_str());
    usage(stderr);
    return 2;
  }
  asio::io_context io;
  tcp::acceptor acceptor(io);
  boost::system::error_code ec;
  acceptor.open(options->listen.protocol(), ec);
  if (!ec)
    acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec)
    acceptor.bind(options->listen, ec);
  if (!ec)
    acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    std::fprintf(stderr, "irgs-linkem: cannot listen on %s:%u: %s\n",
                 options->listen.address().to_string().c_str(), options->listen.port(),
                 ec.message().c_str());
    return 1;
  }
  const tcp::endpoint bound = acceptor.local_endpoint(ec);  // port 0: the one the system chose
  std::printf("linkem: listening on %s:%u, relaying to %s:%u\n",
              bound.address().to_string().c_str(), bound.port(),
              options->connect.address().to_string().c_str(), options->connect.port());
  std::fflush(stdout);
  int connections = 0;
  accept(acceptor, *options, connections);
  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code&, int) { io.stop(); });
  io.run();
  return 0;
}
