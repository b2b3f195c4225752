#pragma once
// Serial port transport: USB-UART adapters, on-board UARTs, USB CDC-ACM boards and Bluetooth SPP
// bound with `rfcomm bind` (/dev/rfcommN). 8 data bits, no parity, 1 stop bit.

#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport.hpp"

#include <memory>
#include <string>

namespace irgs::comms {

enum class FlowControl { kNone, kHardware };  // hardware = RTS/CTS

struct SerialOptions {
  std::string device;          // e.g. /dev/ttyUSB0, /dev/rfcomm0, /dev/pts/3
  std::uint32_t baud = 57600;  // any rate termios knows (9600 ... 921600 and beyond)
  FlowControl flow = FlowControl::kNone;
  bool exclusive = true;  // TIOCEXCL: a second program cannot open the port meanwhile
  std::size_t tx_queue_bytes = kDefaultTxQueueBytes;
};

// The device is opened on open(); a device that vanishes (USB unplug, Bluetooth drop, pty master
// closed) moves the state to failed with a message naming the device.
std::unique_ptr<Transport> makeSerialTransport(IoThread& io, SerialOptions options,
                                               TransportCallbacks callbacks = {});

}  // namespace irgs::comms
