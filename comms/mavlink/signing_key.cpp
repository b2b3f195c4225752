#include "comms/mavlink/signing_key.hpp"

#include <cctype>
#include <fstream>
#include <random>
#include <system_error>

#include "comms/mavlink/sha256.hpp"

namespace irgs::comms::mavlink {
namespace {

constexpr char kHexDigits[] = "0123456789abcdef";

int hexValue(char c) {
  if (c >= '0' && c <= '9')
    return c - '0';
  const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower >= 'a' && lower <= 'f')
    return lower - 'a' + 10;
  return -1;
}

std::string_view trimmed(std::string_view text) {
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && space(text.front()))
    text.remove_prefix(1);
  while (!text.empty() && space(text.back()))
    text.remove_suffix(1);
  return text;
}

}  // namespace

SigningKeyResult parseSigningKeyText(std::string_view text) {
  const std::string_view digits = trimmed(text);
  constexpr std::size_t kDigits = 2 * SigningKey{}.size();
  if (digits.size() != kDigits)
    return {std::nullopt, "a signing key is " + std::to_string(kDigits) +
                              " hexadecimal digits (32 bytes), got " +
                              std::to_string(digits.size()) + " characters"};
  SigningKey key{};
  for (std::size_t i = 0; i < key.size(); ++i) {
    const int high = hexValue(digits[2 * i]);
    const int low = hexValue(digits[2 * i + 1]);
    if (high < 0 || low < 0)
      return {std::nullopt, "a signing key is hexadecimal digits only (0-9, a-f); character " +
                                std::to_string(2 * i + (high < 0 ? 1 : 2)) + " is not one"};
    key[i] = static_cast<std::uint8_t>(high * 16 + low);
  }
  return {key, {}};
}

std::string signingKeyText(const SigningKey& key) {
  std::string out;
  out.reserve(2 * key.size());
  for (const std::uint8_t byte : key) {
    out += kHexDigits[byte >> 4];
    out += kHexDigits[byte & 0x0f];
  }
  return out;
}

std::string signingKeyFingerprint(const SigningKey& key) {
  Sha256 sha;
  sha.update(key);
  const Sha256Digest digest = sha.finish();
  std::string out;
  for (std::size_t i = 0; i < 8; ++i) {
    if (i > 0 && i % 2 == 0)
      out += ' ';
    out += kHexDigits[digest[i] >> 4];
    out += kHexDigits[digest[i] & 0x0f];
  }
  return out;
}

SigningKeyResult loadSigningKeyFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return {std::nullopt, "cannot read signing key file " + path.string()};
  // A key file is 65 bytes; read a little more than that so a wrong file is reported, not read.
  std::string text(256, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  SigningKeyResult result = parseSigningKeyText(text);
  if (!result.key)
    result.error = path.string() + ": " + result.error;
  return result;
}

std::string saveSigningKeyFile(const std::filesystem::path& path, const SigningKey& key) {
  namespace fs = std::filesystem;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out)
      return "cannot write signing key file " + path.string();
    // Restrict before the key goes in.
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write, ec);
    if (ec)
      return "cannot restrict the permissions of " + path.string() + ": " + ec.message();
    out << signingKeyText(key) << '\n';
    if (!out.flush())
      return "cannot write signing key file " + path.string();
  }
  return {};
}

SigningKey randomSigningKey() {
  std::random_device source;
  SigningKey key{};
  for (std::size_t i = 0; i < key.size(); i += 4) {
    const std::uint32_t word = source();
    for (std::size_t b = 0; b < 4; ++b)
      key[i + b] = static_cast<std::uint8_t>(word >> (8 * b));
  }
  return key;
}

}  // namespace irgs::comms::mavlink
