// Interoperability with node-mavlink, an independent implementation: it must decode our frames
// (signed ones included) and we must decode its frames. The test installs node-mavlink with npm
// into the build tree on first run and reports SKIPPED (never passed) when node/npm are missing
// or the package cannot be installed.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::comms::mavlink {
namespace {

namespace fs = std::filesystem;

std::optional<std::string> runCommand(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    return std::nullopt;
  }
  std::string out;
  std::array<char, 4096> buf{};
  while (const std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) {
    out.append(buf.data(), n);
  }
  return ::pclose(pipe) == 0 ? std::optional(out) : std::nullopt;
}

std::string toHex(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t b : bytes) {
    s += kDigits[b >> 4];
    s += kDigits[b & 0x0F];
  }
  return s;
}

std::vector<std::uint8_t> fromHex(const std::string& hex) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  }
  return bytes;
}

SigningKey testKey() {
  SigningKey key{};
  for (std::size_t i = 0; i < key.size(); ++i) {
    key[i] = static_cast<std::uint8_t>(i);
  }
  return key;
}

// Prepares node-mavlink next to the script; returns the directory or a reason to skip.
std::optional<fs::path> prepareNode(std::string& why) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0) {
    why = "node or npm not installed";
    return std::nullopt;
  }
  const fs::path dir = IRGS_NODE_INTEROP_DIR;
  fs::create_directories(dir);
  if (!fs::exists(dir / "node_modules/node-mavlink/package.json")) {
    std::ofstream(dir / "package.json") << R"({"name": "irgs-node-interop", "private": true})";
    const std::string install = "cd '" + dir.string() +
                                "' && npm install --no-audit --no-fund node-mavlink@2.3.0 "
                                ">npm.log 2>&1";
    if (std::system(install.c_str()) != 0) {
      why = "npm could not install node-mavlink (offline?), see " + (dir / "npm.log").string();
      return std::nullopt;
    }
  }
  fs::copy_file(fs::path(IRGS_SOURCE_DIR) / "tests/comms/mavlink/node_interop/interop.mjs",
                dir / "interop.mjs", fs::copy_options::overwrite_existing);
  return dir;
}

TEST(NodeMavlinkInterop, EachSideDecodesTheOthersFrames) {
  std::string why;
  const std::optional<fs::path> dir = prepareNode(why);
  if (!dir) {
    GTEST_SKIP() << why;
  }

  // Ours, covering trimming, extensions, a 24-bit id above 255 and signing.
  FrameEncoder encoder(1, 1);
  std::vector<std::uint8_t> ours;
  auto add = [&](const EncodedFrame& f) {
    ours.insert(ours.end(), f.view().begin(), f.view().end());
  };
  Heartbeat hb;
  hb.custom_mode = 0x01020304;
  hb.type = static_cast<std::uint8_t>(MavType::kGroundRover);
  add(encoder.encode(hb));
  CommandLong cmd;
  cmd.command = static_cast<std::uint16_t>(MavCmd::kIrgsMoveDistance);
  cmd.param1 = 1.5f;
  cmd.target_system = 1;
  add(encoder.encode(cmd));
  Statustext st;
  setString(st.text, "hello from irgs");
  add(encoder.encode(st));
  Odometry od;
  od.x = 1.25f;
  od.q = {1, 0, 0, 0};
  od.frame_id = 1;
  od.reset_counter = 3;
  od.quality = 77;
  add(encoder.encode(od));
  DistanceSensor ds;
  ds.current_distance = 123;
  ds.horizontal_fov = 0.5f;
  add(encoder.encode(ds));
  MissionItemInt item;
  item.seq = 4;
  item.x = 12500;
  item.command = static_cast<std::uint16_t>(MavCmd::kNavWaypoint);
  add(encoder.encode(item));
  FrameEncoder signer(1, 1);
  signer.enableSigning(testKey(), 2);
  add(signer.encode(hb, 1000));
  std::ofstream(*dir / "ours.hex") << toHex(ours);

  const std::optional<std::string> out =
      runCommand("cd '" + dir->string() + "' && node interop.mjs ours.hex 2>&1");
  ASSERT_TRUE(out.has_value()) << "node interop.mjs failed";
  std::vector<std::string> decoded;
  std::string theirs;
  std::istringstream lines(*out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("decoded ", 0) == 0) {
      decoded.push_back(line);
    } else if (line.rfind("theirs ", 0) == 0) {
      theirs = line.substr(7);
    }
  }
  ASSERT_EQ(decoded.size(), 7u) << *out;
  auto expectIn = [&](std::size_t i, const std::string& prefix, const std::string& field) {
    EXPECT_EQ(decoded[i].rfind(prefix, 0), 0u) << decoded[i];
    EXPECT_NE(decoded[i].find(field), std::string::npos) << decoded[i];
  };
  expectIn(0, "decoded 0 0 1 1 unsigned", "\"customMode\":16909060");
  expectIn(1, "decoded 76 1 1 1 unsigned", "\"command\":48100");
  expectIn(1, "decoded 76", "\"_param1\":1.5");
  expectIn(2, "decoded 253 2 1 1 unsigned", "\"text\":\"hello from irgs\"");
  expectIn(3, "decoded 331 3", "\"resetCounter\":3");
  expectIn(3, "decoded 331", "\"quality\":77");
  expectIn(4, "decoded 132 4", "\"horizontalFov\":0.5");
  expectIn(5, "decoded 73 5", "\"x\":12500");
  expectIn(6, "decoded 0 0 1 1 sig-ok", "\"customMode\":16909060");

  // Theirs.
  FrameDecoder decoder(DecoderConfig{.signing_key = testKey()});
  const DecodeResult r = decoder.feed(fromHex(theirs));
  ASSERT_EQ(r.frames.size(), 6u);
  EXPECT_EQ(r.counters.garbage_bytes, 0u);
  EXPECT_EQ(r.frames[0].system_id, 7);
  EXPECT_EQ(r.frames[0].component_id, 9);
  EXPECT_EQ(r.frames[0].as<Heartbeat>()->custom_mode, 0x01020304u);
  const auto c = r.frames[1].as<CommandLong>();
  ASSERT_TRUE(c);
  EXPECT_EQ(c->command, 48101);
  EXPECT_EQ(c->param1, -0.75f);
  EXPECT_EQ(c->confirmation, 2);
  EXPECT_EQ(toStringView(r.frames[2].as<Statustext>()->text), "hello from node");
  const auto o = r.frames[3].as<Odometry>();
  ASSERT_TRUE(o);
  EXPECT_EQ(o->time_usec, 123456789u);
  EXPECT_EQ(o->y, -2.5f);
  EXPECT_EQ(o->child_frame_id, 12);
  EXPECT_EQ(o->reset_counter, 3);
  EXPECT_EQ(o->quality, 77);
  const auto d = r.frames[4].as<DistanceSensor>();
  ASSERT_TRUE(d);
  EXPECT_EQ(d->current_distance, 123);
  EXPECT_EQ(d->id, 6);
  EXPECT_EQ(d->horizontal_fov, 0.5f);
  EXPECT_TRUE(r.frames[5].is_signed);
  EXPECT_TRUE(r.frames[5].signature_verified);
  EXPECT_EQ(r.frames[5].link_id, 4);
}

}  // namespace
}  // namespace irgs::comms::mavlink
