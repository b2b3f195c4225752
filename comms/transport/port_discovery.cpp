#include "comms/transport/port_discovery.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <fstream>
#include <optional>
#include <string_view>
#include <tuple>

namespace irgs::comms {
namespace {

namespace fs = std::filesystem;

struct Family {
  std::string_view prefix;
  SerialPortKind kind;
};

constexpr std::array<Family, 5> kFamilies{{
    {"ttyUSB", SerialPortKind::kUsbSerial},
    {"ttyACM", SerialPortKind::kUsbAcm},
    {"ttyAMA", SerialPortKind::kOnboard},
    {"ttyS", SerialPortKind::kOnboard},
    {"rfcomm", SerialPortKind::kBluetooth},
}};

// Family and number of a device name like "ttyUSB12"; nullopt for anything else.
std::optional<std::pair<Family, unsigned>> classify(std::string_view name) {
  for (const auto& family : kFamilies) {
    if (!name.starts_with(family.prefix))
      continue;
    const std::string_view digits = name.substr(family.prefix.size());
    unsigned number = 0;
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
    if (digits.empty() || ec != std::errc{} || ptr != digits.data() + digits.size())
      return std::nullopt;
    return std::pair{family, number};
  }
  return std::nullopt;
}

// First line of a small sysfs/config file, trimmed; empty when unreadable.
std::string readLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line))
    return {};
  const auto end = line.find_last_not_of(" \t\r\n");
  line.erase(end == std::string::npos ? 0 : end + 1);
  return line;
}

std::string linkName(const fs::path& link) {
  std::error_code ec;
  const auto target = fs::read_symlink(link, ec);
  return ec ? std::string{} : target.filename().string();
}

std::uint16_t parseHex16(const std::string& text) {
  unsigned value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value, 16);
  if (ec != std::errc{} || value > 0xFFFF)
    return 0;
  return static_cast<std::uint16_t>(value);
}

// Walks up from the tty's sysfs device to the USB device (the directory holding idVendor).
void fillUsb(const fs::path& sys_root, const fs::path& tty_sys, SerialPortInfo& info) {
  std::error_code ec;
  fs::path dir = fs::canonical(tty_sys / "device", ec);
  if (ec)
    return;
  const fs::path stop = fs::weakly_canonical(sys_root, ec);
  info.driver = linkName(dir / "driver");
  for (int depth = 0; depth < 8 && !dir.empty() && dir != stop && dir != dir.root_path();
       ++depth, dir = dir.parent_path()) {
    if (!fs::exists(dir / "idVendor", ec))
      continue;
    info.vendor_id = parseHex16(readLine(dir / "idVendor"));
    info.product_id = parseHex16(readLine(dir / "idProduct"));
    info.manufacturer = readLine(dir / "manufacturer");
    info.product = readLine(dir / "product");
    info.serial_number = readLine(dir / "serial");
    return;
  }
}

// BlueZ keeps /var/lib/bluetooth/<adapter>/<device>/info with "Name=..." (root-only on most
// systems, so this is best effort).
std::string bluezName(const fs::path& root, const std::string& address) {
  std::error_code ec;
  for (fs::directory_iterator it(root / "var/lib/bluetooth", ec), end; !ec && it != end;
       it.increment(ec)) {
    std::ifstream in(it->path() / address / "info");
    std::string line;
    while (in && std::getline(in, line)) {
      if (line.starts_with("Name="))
        return line.substr(5);
    }
  }
  return {};
}

std::string hex4(std::uint16_t v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(4, '0');
  for (int i = 3; i >= 0; --i, v = static_cast<std::uint16_t>(v >> 4))
    out[static_cast<std::size_t>(i)] = kDigits[v & 0xF];
  return out;
}

std::string describe(const SerialPortInfo& p) {
  switch (p.kind) {
    case SerialPortKind::kBluetooth: {
      std::string text = "Bluetooth SPP";
      if (!p.bluetooth_name.empty())
        text += " " + p.bluetooth_name;
      if (!p.bluetooth_address.empty())
        text += " [" + p.bluetooth_address + "]";
      if (p.rfcomm_channel >= 0)
        text += " channel " + std::to_string(p.rfcomm_channel);
      return text;
    }
    case SerialPortKind::kOnboard:
      return "Onboard serial port" + (p.driver.empty() ? std::string{} : " (" + p.driver + ")");
    case SerialPortKind::kUsbSerial:
    case SerialPortKind::kUsbAcm: {
      std::string text = p.product.empty()
                             ? std::string(p.kind == SerialPortKind::kUsbAcm ? "USB CDC-ACM device"
                                                                             : "USB serial adapter")
                             : p.product;
      if (!p.manufacturer.empty())
        text += " (" + p.manufacturer + ")";
      if (p.vendor_id != 0 || p.product_id != 0)
        text += " [" + hex4(p.vendor_id) + ":" + hex4(p.product_id) + "]";
      if (!p.serial_number.empty())
        text += " s/n " + p.serial_number;
      return text;
    }
  }
  return {};
}

}  // namespace

std::vector<SerialPortInfo> discoverSerialPorts(const std::filesystem::path& root) {
  const fs::path dev = root / "dev";
  const fs::path sys_root = root / "sys";
  const fs::path tty_class = sys_root / "class/tty";

  struct Entry {
    SerialPortInfo info;
    std::string_view prefix;
    unsigned number;
  };
  std::vector<Entry> entries;
  std::error_code ec;
  for (fs::directory_iterator it(dev, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const auto family = classify(name);
    if (!family)
      continue;
    SerialPortInfo info;
    info.path = "/dev/" + name;
    info.kind = family->first.kind;
    const fs::path tty_sys = tty_class / name;
    std::error_code sys_ec;
    switch (info.kind) {
      case SerialPortKind::kBluetooth:
        // rfcomm's tty exposes the remote address and channel as attributes.
        // The kernel prints the address in lower case; BlueZ names its cache directories in upper.
        info.bluetooth_address = readLine(tty_sys / "address");
        std::transform(info.bluetooth_address.begin(), info.bluetooth_address.end(),
                       info.bluetooth_address.begin(),
                       [](char c) { return c >= 'a' && c <= 'f' ? static_cast<char>(c - 32) : c; });
        if (const auto ch = readLine(tty_sys / "channel"); !ch.empty()) {
          int value = -1;
          std::from_chars(ch.data(), ch.data() + ch.size(), value);
          info.rfcomm_channel = value;
        }
        if (!info.bluetooth_address.empty())
          info.bluetooth_name = bluezName(root, info.bluetooth_address);
        break;
      case SerialPortKind::kOnboard: {
        if (!fs::exists(tty_sys / "device", sys_ec))
          continue;  // no hardware behind this node
        // The 8250 driver registers placeholder ttyS ports on the 'platform' bus; real UARTs sit
        // on pnp/pci/acpi (PCs) or amba/platform for SoC UARTs named ttyAMA.
        if (family->first.prefix == "ttyS" && linkName(tty_sys / "device/subsystem") == "platform")
          continue;
        info.driver = linkName(tty_sys / "device/driver");
        break;
      }
      case SerialPortKind::kUsbSerial:
      case SerialPortKind::kUsbAcm:
        fillUsb(sys_root, tty_sys, info);
        break;
    }
    entries.push_back({std::move(info), family->first.prefix, family->second});
  }

  // Stable names: /dev/serial/by-id/<name> -> ../../ttyUSB0
  for (fs::directory_iterator it(dev / "serial/by-id", ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string target = linkName(it->path());
    for (auto& e : entries) {
      if (e.info.by_id.empty() && e.info.path == "/dev/" + target)
        e.info.by_id = "/dev/serial/by-id/" + it->path().filename().string();
    }
  }

  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tuple(static_cast<int>(a.info.kind), a.prefix, a.number) <
           std::tuple(static_cast<int>(b.info.kind), b.prefix, b.number);
  });
  std::vector<SerialPortInfo> out;
  out.reserve(entries.size());
  for (auto& e : entries) {
    e.info.description = describe(e.info);
    out.push_back(std::move(e.info));
  }
  return out;
}

}  // namespace irgs::comms
