#include "comms/link/link_url.hpp"

#include <charconv>
#include <string_view>

namespace irgs::comms {
namespace {

template <typename T>
std::optional<T> parseNumber(std::string_view text) {
  T value{};
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc{} || ptr != end)
    return std::nullopt;
  return value;
}

LinkUrlResult fail(std::string message) {
  return {std::nullopt, std::move(message)};
}

}  // namespace

LinkUrlResult parseLinkUrl(const std::string& text) {
  const auto scheme_end = text.find("://");
  if (scheme_end == std::string::npos)
    return fail("missing '://' in link URL '" + text + "'");
  const std::string scheme = text.substr(0, scheme_end);
  std::string rest = text.substr(scheme_end + 3);

  LinkUrl url;
  if (const auto q = rest.find('?'); q != std::string::npos) {
    std::string_view query = std::string_view(rest).substr(q + 1);
    while (!query.empty()) {
      const auto amp = query.find('&');
      const std::string_view item = query.substr(0, amp);
      const auto eq = item.find('=');
      const std::string key(item.substr(0, eq));
      const std::string value(eq == std::string_view::npos ? "" : item.substr(eq + 1));
      if (key.empty())
        return fail("empty query parameter in '" + text + "'");
      url.options[key] = value;
      query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    }
    rest.resize(q);
  }

  if (scheme == "serial") {
    url.scheme = LinkScheme::kSerial;
    if (rest.empty())
      return fail("serial URL needs a device path, e.g. serial:///dev/ttyUSB0");
    url.device = rest;
    if (auto it = url.options.find("baud"); it != url.options.end()) {
      const auto baud = parseNumber<std::uint32_t>(it->second);
      if (!baud || *baud == 0)
        return fail("invalid baud rate '" + it->second + "'");
      url.baud = *baud;
      url.options.erase(it);
    }
    return {url, {}};
  }
  if (scheme == "tcp" || scheme == "udp") {
    url.scheme = scheme == "tcp" ? LinkScheme::kTcp : LinkScheme::kUdp;
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos)
      return fail(scheme + " URL needs a port, e.g. " + scheme + "://host:5760");
    url.host = rest.substr(0, colon);
    const auto port = parseNumber<std::uint16_t>(std::string_view(rest).substr(colon + 1));
    if (!port || *port == 0)
      return fail("invalid port in '" + text + "'");
    url.port = *port;
    if (auto it = url.options.find("baud"); it != url.options.end()) {
      const auto baud = parseNumber<std::uint32_t>(it->second);
      if (!baud || *baud == 0)
        return fail("invalid baud rate '" + it->second + "'");
    }
    return {url, {}};
  }
  return fail("unknown link scheme '" + scheme + "' (use serial, tcp or udp)");
}

std::optional<std::uint32_t> linkBaud(const LinkUrl& url) {
  if (url.scheme == LinkScheme::kSerial)
    return url.baud;
  const auto it = url.options.find("baud");
  if (it == url.options.end())
    return std::nullopt;
  const auto baud = parseNumber<std::uint32_t>(it->second);
  return baud && *baud > 0 ? baud : std::nullopt;
}

std::string LinkUrl::toString() const {
  std::string out;
  switch (scheme) {
    case LinkScheme::kSerial:
      out = "serial://" + device + "?baud=" + std::to_string(baud);
      break;
    case LinkScheme::kTcp:
    case LinkScheme::kUdp:
      out = (scheme == LinkScheme::kTcp ? "tcp://" : "udp://") + host + ":" + std::to_string(port);
      break;
  }
  char sep = out.find('?') == std::string::npos ? '?' : '&';
  for (const auto& [key, value] : options) {
    out += sep + key + "=" + value;
    sep = '&';
  }
  return out;
}

}  // namespace irgs::comms
