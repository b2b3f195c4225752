#include "comms/mavlink/signing.hpp"

#include <algorithm>

#include "comms/mavlink/sha256.hpp"

namespace irgs::comms::mavlink {

Signature computeSignature(const SigningKey& key,
                           std::span<const std::uint8_t> frame_before_signature) {
  Sha256 sha;
  sha.update(key);
  sha.update(frame_before_signature);
  const Sha256Digest digest = sha.finish();
  Signature signature{};
  std::copy_n(digest.begin(), signature.size(), signature.begin());
  return signature;
}

std::uint64_t signingTimestampAt(std::chrono::system_clock::time_point time) {
  using std::chrono::duration_cast;
  using std::chrono::microseconds;
  const auto epoch =
      std::chrono::system_clock::time_point{std::chrono::seconds{kSigningEpochUnixSeconds}};
  if (time <= epoch) {
    return 0;
  }
  const auto us = duration_cast<microseconds>(time - epoch).count();
  return (static_cast<std::uint64_t>(us) / 10) & kSigningTimestampMask;
}

SigningKey signingKeyFromPassphrase(std::string_view passphrase) {
  Sha256 sha;
  sha.update(passphrase);
  return sha.finish();
}

}  // namespace irgs::comms::mavlink
