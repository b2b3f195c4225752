#include "comms/transport/port_discovery.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

namespace irgs::comms {
namespace {

namespace fs = std::filesystem;

// A fake / with just enough /dev and /sys for the discovery code, in a fresh temp directory.
class FakeRoot {
 public:
  FakeRoot() {
    std::mt19937_64 rng(std::random_device{}());
    root_ = fs::temp_directory_path() / ("irgs-ports-" + std::to_string(rng()));
    fs::create_directories(root_);
  }
  ~FakeRoot() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  const fs::path& path() const { return root_; }

  void file(const std::string& rel, const std::string& content = {}) const {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << content;
  }
  void dir(const std::string& rel) const { fs::create_directories(root_ / rel); }
  // Symlink root/rel -> target (relative targets are kept as written, like sysfs does).
  void link(const std::string& rel, const std::string& target) const {
    fs::create_directories((root_ / rel).parent_path());
    fs::create_directory_symlink(target, root_ / rel);
  }

 private:
  fs::path root_;
};

// An FTDI adapter as sysfs shows it: class/tty/ttyUSB0 -> .../usb1/1-2/1-2:1.0/ttyUSB0/tty/ttyUSB0
void addFtdi(const FakeRoot& r) {
  const std::string usb = "sys/devices/pci0000:00/0000:00:14.0/usb1/1-2";
  r.file(usb + "/idVendor", "0403\n");
  r.file(usb + "/idProduct", "6001\n");
  r.file(usb + "/manufacturer", "FTDI\n");
  r.file(usb + "/product", "FT232R USB UART\n");
  r.file(usb + "/serial", "A50285BI\n");
  r.dir("sys/bus/usb-serial/drivers/ftdi_sio");
  r.dir(usb + "/1-2:1.0/ttyUSB0/tty/ttyUSB0");
  r.link(usb + "/1-2:1.0/ttyUSB0/driver", "../../../../../../bus/usb-serial/drivers/ftdi_sio");
  r.link(usb + "/1-2:1.0/ttyUSB0/tty/ttyUSB0/device", "../../../ttyUSB0");
  r.link("sys/class/tty/ttyUSB0",
         "../../devices/pci0000:00/0000:00:14.0/usb1/1-2/1-2:1.0/ttyUSB0/tty/ttyUSB0");
  r.file("dev/ttyUSB0");
  r.link("dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A50285BI-if00-port0", "../../ttyUSB0");
}

TEST(PortDiscovery, DescribesUsbAcmOnboardAndBluetoothPortsFromSysfs) {
  FakeRoot r;
  addFtdi(r);
  // CDC-ACM board without strings, only ids.
  r.file("sys/devices/usb1/1-3/idVendor", "2341\n");
  r.file("sys/devices/usb1/1-3/idProduct", "0043\n");
  r.dir("sys/devices/usb1/1-3/1-3:1.0/tty/ttyACM0");
  r.link("sys/devices/usb1/1-3/1-3:1.0/tty/ttyACM0/device", "../../../1-3:1.0");
  r.link("sys/class/tty/ttyACM0", "../../devices/usb1/1-3/1-3:1.0/tty/ttyACM0");
  r.file("dev/ttyACM0");
  // A real 16550 on the PNP bus, and a placeholder on the platform bus.
  r.dir("sys/bus/pnp/drivers/serial");
  r.dir("sys/bus/platform");
  r.dir("sys/devices/pnp0/00:05");
  r.link("sys/devices/pnp0/00:05/subsystem", "../../../bus/pnp");
  r.link("sys/devices/pnp0/00:05/driver", "../../../bus/pnp/drivers/serial");
  r.dir("sys/devices/platform/serial8250");
  r.link("sys/devices/platform/serial8250/subsystem", "../../../bus/platform");
  r.dir("sys/class/tty/ttyS0");
  r.link("sys/class/tty/ttyS0/device", "../../../devices/pnp0/00:05");
  r.dir("sys/class/tty/ttyS1");
  r.link("sys/class/tty/ttyS1/device", "../../../devices/platform/serial8250");
  r.file("dev/ttyS0");
  r.file("dev/ttyS1");
  r.file("dev/ttyS2");  // node without any sysfs device: skipped
  // HC-05 bound with `rfcomm bind 0 98:D3:31:F5:2A:11 1`.
  r.file("sys/class/tty/rfcomm0/address", "98:d3:31:f5:2a:11\n");
  r.file("sys/class/tty/rfcomm0/channel", "1\n");
  r.file("var/lib/bluetooth/00:1A:7D:DA:71:13/98:D3:31:F5:2A:11/info",
         "[General]\nName=HC-05\nClass=0x001f00\n");
  r.file("dev/rfcomm0");
  // Not serial ports.
  r.file("dev/tty0");
  r.file("dev/ttyUSBx");
  r.file("dev/null");

  const auto ports = discoverSerialPorts(r.path());
  ASSERT_EQ(ports.size(), 4u);

  EXPECT_EQ(ports[0].path, "/dev/ttyUSB0");
  EXPECT_EQ(ports[0].kind, SerialPortKind::kUsbSerial);
  EXPECT_EQ(ports[0].vendor_id, 0x0403);
  EXPECT_EQ(ports[0].product_id, 0x6001);
  EXPECT_EQ(ports[0].manufacturer, "FTDI");
  EXPECT_EQ(ports[0].serial_number, "A50285BI");
  EXPECT_EQ(ports[0].driver, "ftdi_sio");
  EXPECT_EQ(ports[0].by_id, "/dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A50285BI-if00-port0");
  EXPECT_EQ(ports[0].description, "FT232R USB UART (FTDI) [0403:6001] s/n A50285BI");

  EXPECT_EQ(ports[1].path, "/dev/ttyACM0");
  EXPECT_EQ(ports[1].kind, SerialPortKind::kUsbAcm);
  EXPECT_EQ(ports[1].description, "USB CDC-ACM device [2341:0043]");

  EXPECT_EQ(ports[2].path, "/dev/ttyS0");
  EXPECT_EQ(ports[2].kind, SerialPortKind::kOnboard);
  EXPECT_EQ(ports[2].description, "Onboard serial port (serial)");

  EXPECT_EQ(ports[3].path, "/dev/rfcomm0");
  EXPECT_EQ(ports[3].kind, SerialPortKind::kBluetooth);
  EXPECT_EQ(ports[3].bluetooth_address, "98:D3:31:F5:2A:11");
  EXPECT_EQ(ports[3].rfcomm_channel, 1);
  EXPECT_EQ(ports[3].description, "Bluetooth SPP HC-05 [98:D3:31:F5:2A:11] channel 1");
}

TEST(PortDiscovery, SortsNumbersNaturally) {
  FakeRoot r;
  for (const char* name : {"ttyUSB10", "ttyUSB2", "ttyUSB0", "rfcomm1", "ttyACM1"})
    r.file(std::string("dev/") + name);
  const auto ports = discoverSerialPorts(r.path());
  std::vector<std::string> paths;
  for (const auto& p : ports)
    paths.push_back(p.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"/dev/ttyUSB0", "/dev/ttyUSB2", "/dev/ttyUSB10",
                                             "/dev/ttyACM1", "/dev/rfcomm1"}));
  EXPECT_EQ(ports[0].description, "USB serial adapter");
  EXPECT_EQ(ports[4].description, "Bluetooth SPP");
}

TEST(PortDiscovery, ReturnsNothingForAMissingRoot) {
  EXPECT_TRUE(discoverSerialPorts("/nonexistent/irgs-root").empty());
}

TEST(PortDiscovery, RunsOnTheRealSystemWithoutThrowing) {
  // Whatever this machine has; every entry must at least be a described /dev path.
  for (const auto& port : discoverSerialPorts()) {
    EXPECT_TRUE(port.path.starts_with("/dev/")) << port.path;
    EXPECT_FALSE(port.description.empty()) << port.path;
  }
}

}  // namespace
}  // namespace irgs::comms
