// CRC_EXTRA and payload lengths recomputed from the XML definitions in resources/mavlink/, with
// an XML reader written here, independent of scripts/mavlink_gen.py which made the constants.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "comms/mavlink/crc.hpp"
#include "comms/mavlink/message_info.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::comms::mavlink {
namespace {

struct XmlField {
  std::string type;  // element type, without [N]
  std::string name;
  std::size_t array_length = 0;
  bool extension = false;
};

struct XmlMessage {
  std::uint32_t id = 0;
  std::string name;
  std::vector<XmlField> fields;
};

using Attributes = std::map<std::string, std::string>;

// A tag scanner sufficient for MAVLink definition files: comments, processing instructions,
// start/end/empty-element tags with double-quoted attributes, and text content.
std::filesystem::path resolveInclude(const std::filesystem::path& from, const std::string& name) {
  const auto beside = from.parent_path() / name;
  if (std::filesystem::exists(beside))
    return beside;
  return std::filesystem::path(IRGS_SOURCE_DIR) / "../shared/mavlink" / name;
}

class DefinitionReader {
 public:
  void load(const std::filesystem::path& file) {
    if (!loaded_.insert(file.filename().string()).second) {
      return;
    }
    std::ifstream in(file);
    ASSERT_TRUE(in) << "cannot open " << file;
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::size_t pos = 0;
    XmlMessage* current = nullptr;
    bool extensions = false;
    while ((pos = text.find('<', pos)) != std::string::npos) {
      if (text.compare(pos, 4, "<!--") == 0) {
        pos = text.find("-->", pos) + 3;
        continue;
      }
      const std::size_t close = text.find('>', pos);
      ASSERT_NE(close, std::string::npos);
      std::string tag = text.substr(pos + 1, close - pos - 1);
      pos = close + 1;
      if (tag.empty() || tag[0] == '?') {
        continue;
      }
      if (tag[0] == '/') {
        if (tag == "/message") {
          current = nullptr;
        }
        continue;
      }
      if (tag.back() == '/') {
        tag.pop_back();
      }
      std::string name;
      const Attributes attrs = parseTag(tag, name);
      if (name == "include") {
        const std::string inc = text.substr(pos, text.find('<', pos) - pos);
        const auto b = inc.find_first_not_of(" \t\r\n");
        const auto e = inc.find_last_not_of(" \t\r\n");
        load(resolveInclude(file, inc.substr(b, e - b + 1)));
      } else if (name == "message") {
        messages_.push_back(
            {static_cast<std::uint32_t>(std::stoul(attrs.at("id"))), attrs.at("name"), {}});
        current = &messages_.back();
        extensions = false;
      } else if (name == "extensions" && current != nullptr) {
        extensions = true;
      } else if (name == "field" && current != nullptr) {
        XmlField f;
        f.type = attrs.at("type");
        f.name = attrs.at("name");
        f.extension = extensions;
        if (const auto b = f.type.find('['); b != std::string::npos) {
          f.array_length = std::stoul(f.type.substr(b + 1));
          f.type.resize(b);
        }
        current->fields.push_back(f);
      }
    }
  }

  const std::vector<XmlMessage>& messages() const { return messages_; }

 private:
  static Attributes parseTag(const std::string& tag, std::string& name) {
    std::size_t i = tag.find_first_of(" \t\r\n");
    name = tag.substr(0, i);
    Attributes attrs;
    while (i != std::string::npos && i < tag.size()) {
      const std::size_t eq = tag.find('=', i);
      if (eq == std::string::npos) {
        break;
      }
      const std::size_t k = tag.find_first_not_of(" \t\r\n", i);
      const std::size_t q1 = tag.find('"', eq);
      const std::size_t q2 = tag.find('"', q1 + 1);
      attrs[tag.substr(k, eq - k)] = tag.substr(q1 + 1, q2 - q1 - 1);
      i = q2 + 1;
    }
    return attrs;
  }

  std::set<std::string> loaded_;
  std::vector<XmlMessage> messages_;
};

std::size_t typeSize(const std::string& type) {
  static const std::map<std::string, std::size_t> kSizes = {
      {"char", 1},     {"uint8_t", 1},  {"int8_t", 1},   {"uint8_t_mavlink_version", 1},
      {"uint16_t", 2}, {"int16_t", 2},  {"uint32_t", 4}, {"int32_t", 4},
      {"float", 4},    {"uint64_t", 8}, {"int64_t", 8},  {"double", 8}};
  return kSizes.at(type);
}

struct Layout {
  std::uint8_t crc_extra = 0;
  std::size_t min_length = 0;
  std::size_t max_length = 0;
};

// https://mavlink.io/en/guide/serialization.html#crc_extra
Layout layoutOf(const XmlMessage& m) {
  std::vector<XmlField> base;
  Layout layout;
  for (const XmlField& f : m.fields) {
    const std::size_t bytes = typeSize(f.type) * std::max<std::size_t>(1, f.array_length);
    layout.max_length += bytes;
    if (!f.extension) {
      base.push_back(f);
      layout.min_length += bytes;
    }
  }
  std::stable_sort(base.begin(), base.end(), [](const XmlField& a, const XmlField& b) {
    return typeSize(a.type) > typeSize(b.type);
  });
  std::uint16_t crc = crcAccumulate(m.name + " ");
  for (const XmlField& f : base) {
    const std::string type = f.type == "uint8_t_mavlink_version" ? "uint8_t" : f.type;
    crc = crcAccumulate(type + " ", crc);
    crc = crcAccumulate(f.name + " ", crc);
    if (f.array_length > 0) {
      crc = crcAccumulate(static_cast<std::uint8_t>(f.array_length), crc);
    }
  }
  layout.crc_extra = foldCrcExtra(crc);
  return layout;
}

// The official definitions are not copied into the project (shared/mavlink/README.md): an include
// resolves beside the including file first, then in ../shared/mavlink.
const std::filesystem::path kOfficialDir =
    std::filesystem::path(IRGS_SOURCE_DIR) / "../shared/mavlink";

bool officialDefinitionsPresent() {
  return std::filesystem::exists(kOfficialDir / "common.xml");
}

const std::vector<XmlMessage>& definitions() {
  static const std::vector<XmlMessage> kMessages = [] {
    DefinitionReader reader;
    reader.load(std::filesystem::path(IRGS_SOURCE_DIR) / "resources/mavlink/irgs.xml");
    return reader.messages();
  }();
  return kMessages;
}

TEST(MavlinkCrcExtra, DefinitionsIncludeCommonAndTheDialect) {
  if (!officialDefinitionsPresent()) {
    GTEST_SKIP() << "the official MAVLink XML is read from " << kOfficialDir.string()
                 << ", which is not present (shared/ is optional)";
  }
  std::set<std::string> names;
  for (const XmlMessage& m : definitions()) {
    names.insert(m.name);
  }
  EXPECT_TRUE(names.contains("HEARTBEAT"));     // minimal.xml via standard.xml via common.xml
  EXPECT_TRUE(names.contains("ODOMETRY"));      // common.xml
  EXPECT_TRUE(names.contains("IRGS_CONTACT"));  // irgs.xml
  EXPECT_GT(definitions().size(), 200u);
}

TEST(MavlinkCrcExtra, EveryGeneratedConstantEqualsTheValueComputedFromXml) {
  if (!officialDefinitionsPresent()) {
    GTEST_SKIP() << "the official MAVLink XML is read from " << kOfficialDir.string()
                 << ", which is not present (shared/ is optional)";
  }
  std::map<std::uint32_t, const XmlMessage*> by_id;
  for (const XmlMessage& m : definitions()) {
    EXPECT_TRUE(by_id.emplace(m.id, &m).second) << "duplicate id " << m.id;
  }
  ASSERT_FALSE(generatedMessages().empty());
  for (const MessageInfo& info : generatedMessages()) {
    const auto it = by_id.find(info.id);
    ASSERT_NE(it, by_id.end()) << info.name << " id " << info.id << " not in the XML";
    EXPECT_EQ(it->second->name, info.name);
    const Layout layout = layoutOf(*it->second);
    EXPECT_EQ(info.crc_extra, layout.crc_extra) << info.name;
    EXPECT_EQ(info.min_length, layout.min_length) << info.name;
    EXPECT_EQ(info.max_length, layout.max_length) << info.name;
  }
}

// Values published in the official generated C headers (MAVLINK_MSG_ID_*_CRC), as a check of
// the computation itself.
TEST(MavlinkCrcExtra, MatchesPublishedValuesOfCommonMessages) {
  EXPECT_EQ(Heartbeat::kCrcExtra, 50);
  EXPECT_EQ(SysStatus::kCrcExtra, 124);
  EXPECT_EQ(ParamRequestRead::kCrcExtra, 214);
  EXPECT_EQ(ParamRequestList::kCrcExtra, 159);
  EXPECT_EQ(ParamValue::kCrcExtra, 220);
  EXPECT_EQ(ParamSet::kCrcExtra, 168);
  EXPECT_EQ(RawImu::kCrcExtra, 144);
  EXPECT_EQ(ScaledImu::kCrcExtra, 170);
  EXPECT_EQ(Attitude::kCrcExtra, 39);
  EXPECT_EQ(LocalPositionNed::kCrcExtra, 185);
  EXPECT_EQ(MissionCurrent::kCrcExtra, 28);
  EXPECT_EQ(MissionRequestList::kCrcExtra, 132);
  EXPECT_EQ(MissionCount::kCrcExtra, 221);
  EXPECT_EQ(MissionClearAll::kCrcExtra, 232);
  EXPECT_EQ(MissionItemReached::kCrcExtra, 11);
  EXPECT_EQ(MissionAck::kCrcExtra, 153);
  EXPECT_EQ(ManualControl::kCrcExtra, 243);
  EXPECT_EQ(MissionRequestInt::kCrcExtra, 196);
  EXPECT_EQ(MissionItemInt::kCrcExtra, 38);
  EXPECT_EQ(CommandLong::kCrcExtra, 152);
  EXPECT_EQ(CommandAck::kCrcExtra, 143);
  EXPECT_EQ(Timesync::kCrcExtra, 34);
  EXPECT_EQ(DistanceSensor::kCrcExtra, 85);
  EXPECT_EQ(Statustext::kCrcExtra, 83);
  EXPECT_EQ(Odometry::kCrcExtra, 91);
  EXPECT_EQ(WheelDistance::kCrcExtra, 113);
}

}  // namespace
}  // namespace irgs::comms::mavlink
