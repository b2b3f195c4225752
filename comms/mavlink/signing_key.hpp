#pragma once
// MAVLink signing keys as people handle them: as text, in a key file, by a fingerprint.
//
// Text and key-file format: the 32 key bytes as 64 hexadecimal digits (either case), with
// optional whitespace around them and nothing else, e.g. written by the GUI's connection dialog
// ("Export…") or by `head -c 32 /dev/urandom | xxd -p -c 32`. A key file should be readable by
// its owner only (the GUI and saveSigningKeyFile write it 0600).
// The fingerprint names a key without revealing it: the first 8 bytes of SHA-256(key) as 16
// lowercase hex digits in groups of four ("3f2a 9c1b 0e77 d412"), so two copies can be compared
// by eye (the GUI shows it, irgs-robot prints it at start).

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "comms/mavlink/signing.hpp"

namespace irgs::comms::mavlink {

struct SigningKeyResult {
  std::optional<SigningKey> key;
  std::string error;  // set when key is empty
};

SigningKeyResult parseSigningKeyText(std::string_view text);
std::string signingKeyText(const SigningKey& key);  // 64 lowercase hex digits
std::string signingKeyFingerprint(const SigningKey& key);

// Reads and parses a key file; the error names the file.
SigningKeyResult loadSigningKeyFile(const std::filesystem::path& path);
// Writes signingKeyText(key) and a newline, owner read/write only. Returns an error or "".
std::string saveSigningKeyFile(const std::filesystem::path& path, const SigningKey& key);

// A fresh key from the operating system's random source (std::random_device: getrandom or
// /dev/urandom under libstdc++ on Linux).
SigningKey randomSigningKey();

}  // namespace irgs::comms::mavlink
