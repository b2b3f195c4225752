#pragma once
// Serial and Bluetooth RFCOMM port discovery from /dev and sysfs (Linux). A function of a root
// directory so tests run it on a fake tree; it only reads files and never opens a device.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace irgs::comms {

enum class SerialPortKind {
  kUsbSerial,  // ttyUSB*: FTDI, CP210x, CH340 ... USB-UART bridges
  kUsbAcm,     // ttyACM*: USB CDC-ACM (Arduino-like boards, STM32 VCP)
  kOnboard,    // ttyS* with real hardware behind it, ttyAMA* (Raspberry Pi UART)
  kBluetooth,  // rfcomm*: Bluetooth SPP bound with `rfcomm bind`
};

struct SerialPortInfo {
  std::string path;  // device node as the system sees it, e.g. "/dev/ttyUSB0"
  SerialPortKind kind = SerialPortKind::kUsbSerial;
  std::string description;  // one line for a port picker
  std::string by_id;        // a /dev/serial/by-id symlink to this port (stable across replugs)
  // USB (from the USB device's sysfs attributes)
  std::string manufacturer;
  std::string product;
  std::string serial_number;
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string driver;  // kernel driver, e.g. "ftdi_sio", "cdc_acm", "serial8250"
  // Bluetooth
  std::string bluetooth_address;  // "98:D3:31:F5:2A:11"
  std::string bluetooth_name;     // from BlueZ's device cache, when readable
  int rfcomm_channel = -1;
};

// Lists ttyUSB*, ttyACM*, ttyAMA*, rfcomm* device nodes under root/dev, and the ttyS* ones that
// have hardware behind them (sysfs device whose bus is not the legacy 'platform' placeholder that
// every PC exposes 32 of). Sorted by kind then natural name order (ttyUSB2 before ttyUSB10).
// Unreadable sysfs entries only make descriptions poorer; this never throws for a missing tree.
std::vector<SerialPortInfo> discoverSerialPorts(const std::filesystem::path& root = "/");

}  // namespace irgs::comms
