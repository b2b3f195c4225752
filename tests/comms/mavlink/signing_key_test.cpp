#include "comms/mavlink/signing_key.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace irgs::comms::mavlink {
namespace {

namespace fs = std::filesystem;

SigningKey countingKey() {
  SigningKey key{};
  for (std::size_t i = 0; i < key.size(); ++i)
    key[i] = static_cast<std::uint8_t>(i);
  return key;
}

constexpr char kCountingKeyText[] =
    "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f";

// A file name of its own under the test's temporary directory, removed at the end.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_(fs::temp_directory_path() / (name + "." + std::to_string(::getpid()))) {}
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(SigningKey, TextIsSixtyFourHexDigitsAndRoundTrips) {
  EXPECT_EQ(signingKeyText(countingKey()), kCountingKeyText);
  const SigningKeyResult parsed =
      parseSigningKeyText(std::string("  \n") + kCountingKeyText + "\n");
  ASSERT_TRUE(parsed.key) << parsed.error;
  EXPECT_EQ(*parsed.key, countingKey());
  std::string upper = kCountingKeyText;
  for (char& c : upper)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  EXPECT_EQ(parseSigningKeyText(upper).key, countingKey());
}

TEST(SigningKey, WrongLengthOrNonHexTextIsRefusedWithTheReason) {
  const SigningKeyResult short_key = parseSigningKeyText("0011");
  EXPECT_FALSE(short_key.key);
  EXPECT_NE(short_key.error.find("64 hexadecimal digits"), std::string::npos) << short_key.error;
  std::string bad = kCountingKeyText;
  bad[10] = 'g';
  const SigningKeyResult non_hex = parseSigningKeyText(bad);
  EXPECT_FALSE(non_hex.key);
  EXPECT_NE(non_hex.error.find("character 11"), std::string::npos) << non_hex.error;
  // A passphrase is not a key (signingKeyFromPassphrase makes one from it).
  EXPECT_FALSE(parseSigningKeyText("correct horse battery staple").key);
}

TEST(SigningKey, FingerprintIsTheFirstEightBytesOfItsSha256InGroupsOfFour) {
  // python3: hashlib.sha256(bytes(range(32))).hexdigest()[:16]
  EXPECT_EQ(signingKeyFingerprint(countingKey()), "630d cd29 66c4 3366");
}

TEST(SigningKey, AKeyFileIsWrittenForItsOwnerOnlyAndReadsBack) {
  TempFile file("irgs_signing_key_test.key");
  ASSERT_EQ(saveSigningKeyFile(file.path(), countingKey()), "");
  const fs::perms perms = fs::status(file.path()).permissions();
  EXPECT_EQ(perms & (fs::perms::group_all | fs::perms::others_all), fs::perms::none);
  std::ifstream in(file.path());
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, std::string(kCountingKeyText) + "\n");
  const SigningKeyResult loaded = loadSigningKeyFile(file.path());
  ASSERT_TRUE(loaded.key) << loaded.error;
  EXPECT_EQ(*loaded.key, countingKey());
}

TEST(SigningKey, AMissingOrWrongKeyFileIsAnErrorNamingTheFile) {
  TempFile file("irgs_signing_key_test.txt");
  const SigningKeyResult missing = loadSigningKeyFile(file.path());
  EXPECT_FALSE(missing.key);
  EXPECT_NE(missing.error.find(file.path().string()), std::string::npos) << missing.error;
  std::ofstream(file.path()) << "not a key\n";
  const SigningKeyResult wrong = loadSigningKeyFile(file.path());
  EXPECT_FALSE(wrong.key);
  EXPECT_NE(wrong.error.find(file.path().string() + ": a signing key is"), std::string::npos)
      << wrong.error;
}

TEST(SigningKey, RandomKeysAreFreshEachTime) {
  const SigningKey a = randomSigningKey();
  const SigningKey b = randomSigningKey();
  EXPECT_NE(a, b);  // 2^-256 to fail by chance
  EXPECT_NE(a, SigningKey{});
}

}  // namespace
}  // namespace irgs::comms::mavlink
