#include "comms/transport/serial_transport.hpp"

#include "comms/transport/transport_core.hpp"

#include <boost/asio/error.hpp>
#include <boost/asio/serial_port.hpp>
#include <boost/asio/write.hpp>

#include <sys/ioctl.h>

#include <array>
#include <cerrno>

namespace irgs::comms {
namespace {

namespace asio = boost::asio;

class SerialCore final : public detail::TransportCore {
 public:
  SerialCore(IoThread& io, SerialOptions options, TransportCallbacks callbacks)
      : TransportCore(io, options.tx_queue_bytes,
                      "serial " + options.device + " @" + std::to_string(options.baud),
                      std::move(callbacks)),
        options_(std::move(options)),
        port_(this->io()) {}

 protected:
  void doOpen() override {
    boost::system::error_code ec;
    port_.open(options_.device, ec);
    if (ec) {
      fail("cannot open " + options_.device + ": " + ec.message());
      return;
    }
    if (options_.exclusive)
      ::ioctl(port_.native_handle(), TIOCEXCL);  // best effort: not every driver supports it
    using Base = asio::serial_port_base;
    if (port_.set_option(Base::baud_rate(options_.baud), ec); ec) {
      fail("cannot set " + std::to_string(options_.baud) + " baud on " + options_.device + ": " +
           ec.message() + " (not a rate this system's termios supports?)");
      return;
    }
    const auto flow = options_.flow == FlowControl::kHardware ? Base::flow_control::hardware
                                                              : Base::flow_control::none;
    port_.set_option(Base::character_size(8), ec);
    if (!ec)
      port_.set_option(Base::parity(Base::parity::none), ec);
    if (!ec)
      port_.set_option(Base::stop_bits(Base::stop_bits::one), ec);
    if (!ec)
      port_.set_option(Base::flow_control(flow), ec);
    if (ec) {
      fail("cannot configure " + options_.device + " as 8N1: " + ec.message());
      return;
    }
    setState(TransportState::kOpen, "opened " + description());
    startRead(generation());
  }

  void doClose() override {
    boost::system::error_code ignored;
    port_.close(ignored);
  }

  void doWrite(std::uint64_t gen, TxQueue::Chunk chunk) override {
    const auto buffer = asio::buffer(*chunk);
    asio::async_write(
        port_, buffer,
        [self = self<SerialCore>(), gen, chunk = std::move(chunk)](
            const boost::system::error_code& ec, std::size_t n) { self->writeDone(gen, ec, n); });
  }

 private:
  void startRead(std::uint64_t gen) {
    port_.async_read_some(asio::buffer(rx_), [self = self<SerialCore>(), gen](
                                                 const boost::system::error_code& ec,
                                                 std::size_t n) { self->onRead(gen, ec, n); });
  }

  void onRead(std::uint64_t gen, const boost::system::error_code& ec, std::size_t n) {
    if (!current(gen) || ec == asio::error::operation_aborted)
      return;
    if (ec) {
      fail(describeReadError(ec));
      return;
    }
    deliver(std::span<const std::uint8_t>(rx_.data(), n));
    if (current(gen))  // the callback may have closed us
      startRead(gen);
  }

  std::string describeReadError(const boost::system::error_code& ec) const {
    // A tty that is hung up (USB unplug, Bluetooth drop, pty master closed) reads as end of file;
    // a vanished device node can also fail with EIO/ENODEV/ENXIO.
    if (ec == asio::error::eof)
      return "serial device " + options_.device + " disappeared (hung up)";
    if (ec.category() == boost::system::system_category() &&
        (ec.value() == EIO || ec.value() == ENODEV || ec.value() == ENXIO))
      return "serial device " + options_.device + " disappeared (" + ec.message() + ")";
    return "read error on " + options_.device + ": " + ec.message();
  }

  SerialOptions options_;
  asio::serial_port port_;
  std::array<std::uint8_t, 4096> rx_{};
};

}  // namespace

std::unique_ptr<Transport> makeSerialTransport(IoThread& io, SerialOptions options,
                                               TransportCallbacks callbacks) {
  return std::make_unique<detail::AsioTransport>(
      std::make_shared<SerialCore>(io, std::move(options), std::move(callbacks)));
}

}  // namespace irgs::comms
