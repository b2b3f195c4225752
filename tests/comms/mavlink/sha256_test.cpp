#include "comms/mavlink/sha256.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace irgs::comms::mavlink {
namespace {

std::string hex(const Sha256Digest& d) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t b : d) {
    s += kDigits[b >> 4];
    s += kDigits[b & 0x0F];
  }
  return s;
}

std::string hashOf(std::string_view text) {
  Sha256 sha;
  sha.update(text);
  return hex(sha.finish());
}

// FIPS 180-4 examples (NIST CSRC "SHA256.pdf", "SHA2_Additional.pdf").
TEST(Sha256, MatchesFipsVectorAbc) {
  EXPECT_EQ(hashOf("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, MatchesFipsVectorEmpty) {
  EXPECT_EQ(hashOf(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, MatchesFipsVectorTwoBlocks) {
  EXPECT_EQ(hashOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, MatchesFipsVector896Bits) {
  EXPECT_EQ(hashOf("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnop"
                   "qklmnopqrlmnopqrsmnopqrstnopqrstu"),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256, MatchesFipsVectorMillionA) {
  Sha256 sha;
  const std::string chunk(1000, 'a');
  for (int i = 0; i < 1000; ++i) {
    sha.update(chunk);
  }
  EXPECT_EQ(hex(sha.finish()), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// Lengths around the padding boundary (55/56/63/64/65 bytes); expected values from Python's
// hashlib for bytes (7 i + 1) mod 256.
TEST(Sha256, HandlesEveryPaddingBoundary) {
  const std::vector<std::pair<std::size_t, std::string>> cases = {
      {55, "16fa57a0a3423a715d594516339f36189d6b5f93754a9714fef202616a9fabfe"},
      {56, "c37b44e5f1b18554b36966f4f8e08bfbf3164c4b6c10374d12d89850892073c5"},
      {63, "bbba992d2c85af960fb2987a1fd05e0aa82a3db3c740dd8982a9e273b75e36a3"},
      {64, "66bd4633ed6f71c4ecfa4763bf7ba1c8ec7612de9aa6c0578a7b675207c71e0b"},
      {65, "9f7dc47107b750a1f3d35db5d9547f24ef40da5b731b9540d4f43710a154f6c9"},
      {119, "a3ed307b730fa77c07531300c6e4a282330011d4d4caf6bb7b63ae05950f4b66"},
      {128, "e462c130fef8c97e34f7dc3ff3ad2f8b3533ab849af21c10531552a2852387a4"},
  };
  for (const auto& [n, expected] : cases) {
    std::vector<std::uint8_t> data(n);
    for (std::size_t i = 0; i < n; ++i) {
      data[i] = static_cast<std::uint8_t>(i * 7 + 1);
    }
    EXPECT_EQ(hex(Sha256::hash(data)), expected) << n << " bytes";
    // Fed in two pieces split anywhere, the digest is the same.
    for (std::size_t split = 0; split <= n; ++split) {
      Sha256 sha;
      sha.update(std::span(data).first(split));
      sha.update(std::span(data).subspan(split));
      ASSERT_EQ(hex(sha.finish()), expected) << n << " bytes split at " << split;
    }
  }
}

TEST(Sha256, ResetsAfterFinish) {
  Sha256 sha;
  sha.update("something else");
  (void)sha.finish();
  sha.update("abc");
  EXPECT_EQ(hex(sha.finish()), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace irgs::comms::mavlink
