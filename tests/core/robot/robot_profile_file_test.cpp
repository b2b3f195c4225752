#include "core/robot/robot_profile_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace irgs {
namespace {

using ::testing::HasSubstr;

// A small valid profile; tests replace parts of it.
std::string minimalProfile(const std::string& sonar_extra = "", const std::string& top_extra = "") {
  return R"({
  "name": "square",
  "drive": {"wheel_radius_m": 0.05, "wheelbase_m": 0.3},
  "limits": {"max_turn_rate_degps": 90, "max_speed_mps": 0.5},
  "body_outline": [[0.2, 0.2], [-0.2, 0.2], [-0.2, -0.2], [0.2, -0.2]],
  "sonars": [
    {"name": "front", "x_m": 0.2, "y_m": 0, "heading_deg": 0, "beam_width_deg": 30},
    {"name": "left", "x_m": 0, "y_m": 0.2, "heading_deg": 90)" +
         sonar_extra + R"(}
  ],
  "bumpers": [{"x_m": 0.2, "y_m": 0.0, "normal_deg": 0}],
  "proximity": [{"x_m": -0.2, "y_m": 0, "heading_deg": 180, "max_range_m": 0.25}])" +
         top_extra + "\n}\n";
}

const Diagnostic* findField(const std::vector<Diagnostic>& diagnostics, const std::string& field) {
  for (const auto& d : diagnostics) {
    if (d.field == field)
      return &d;
  }
  return nullptr;
}

TEST(RobotProfileFile, ParsesAProfileAndConvertsDegreesToRadians) {
  const auto result = parseRobotProfileJson(minimalProfile(), "mini.json");
  ASSERT_TRUE(result.ok()) << result.diagnostics.at(0).toString();
  EXPECT_TRUE(result.diagnostics.empty());
  const RobotProfile& p = *result.profile;
  EXPECT_EQ(p.name, "square");
  EXPECT_DOUBLE_EQ(p.drive.wheel_radius_m, 0.05);
  EXPECT_DOUBLE_EQ(p.limits.max_turn_rate_radps, kPi / 2.0);
  EXPECT_DOUBLE_EQ(p.limits.max_accel_mps2, MotionLimits{}.max_accel_mps2);  // default kept
  ASSERT_EQ(p.sonars.size(), 2u);
  EXPECT_DOUBLE_EQ(p.sonars[0].beam_width_rad, degToRad(30.0));
  EXPECT_DOUBLE_EQ(p.sonars[1].mount.theta, kPi / 2.0);
  EXPECT_DOUBLE_EQ(p.sonars[1].beam_width_rad, SonarSpec{}.beam_width_rad);
  ASSERT_EQ(p.bumpers.size(), 1u);
  EXPECT_EQ(p.bumpers[0].name, "bumper_0");
  ASSERT_EQ(p.proximity.size(), 1u);
  EXPECT_DOUBLE_EQ(p.proximity[0].mount.theta, kPi);
  EXPECT_DOUBLE_EQ(p.proximity[0].max_range_m, 0.25);
}

TEST(RobotProfileFile, BodyRadiusIsTheFarthestOutlineVertex) {
  const auto result = parseRobotProfileJson(minimalProfile(), "mini.json");
  ASSERT_TRUE(result.ok());
  EXPECT_DOUBLE_EQ(result.profile->bodyRadius(), std::sqrt(0.08));
  EXPECT_DOUBLE_EQ(RobotProfile{}.bodyRadius(), 0.0);
}

TEST(RobotProfileFile, StoresAClockwiseOutlineCounterClockwise) {
  const auto result = parseRobotProfileJson(minimalProfile(), "mini.json");
  ASSERT_TRUE(result.ok());
  const auto& poly = result.profile->body_outline;
  double twice_area = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    twice_area += cross(poly[i], poly[(i + 1) % poly.size()]);
  EXPECT_GT(twice_area, 0.0);
}

TEST(RobotProfileFile, ReportsJsonSyntaxErrorsWithLineAndColumn) {
  const std::string text = "{\n  \"name\": \"x\",\n  \"drive\": {,}\n}";
  const auto result = parseRobotProfileJson(text, "broken.json");
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.diagnostics.size(), 1u);
  const Diagnostic& d = result.diagnostics[0];
  EXPECT_EQ(d.file, "broken.json");
  EXPECT_EQ(d.line, 3);
  EXPECT_EQ(d.column, 13);
  EXPECT_THAT(d.message, HasSubstr("invalid JSON"));
}

TEST(RobotProfileFile, NamesTheFieldOfAnOutOfRangeValueWithItsLine) {
  const auto result =
      parseRobotProfileJson(minimalProfile(", \"beam_width_deg\": 200"), "mini.json");
  ASSERT_FALSE(result.ok());
  const Diagnostic* d = findField(result.diagnostics, "/sonars/1/beam_width_deg");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::kError);
  EXPECT_EQ(d->line, 8);
  EXPECT_GT(d->column, 0);
  EXPECT_THAT(d->message, HasSubstr("(0, 180]"));
  EXPECT_THAT(d->toString(), HasSubstr("mini.json:8:"));
}

TEST(RobotProfileFile, ReportsMissingAndMistypedFields) {
  const std::string text = R"({
  "drive": {"wheel_radius_m": "big"},
  "body_outline": [[0, 0], [1, 0]],
  "sonars": [{"y_m": 0, "heading_deg": 0}],
  "bumpers": 3
})";
  const auto result = parseRobotProfileJson(text, "bad.json");
  ASSERT_FALSE(result.ok());
  EXPECT_NE(findField(result.diagnostics, "/name"), nullptr);
  EXPECT_NE(findField(result.diagnostics, "/drive/wheel_radius_m"), nullptr);
  EXPECT_NE(findField(result.diagnostics, "/drive/wheelbase_m"), nullptr);
  EXPECT_NE(findField(result.diagnostics, "/body_outline"), nullptr);
  const Diagnostic* missing_x = findField(result.diagnostics, "/sonars/0/x_m");
  ASSERT_NE(missing_x, nullptr);
  EXPECT_EQ(missing_x->line, 4);  // located at the object the key is missing from
  EXPECT_NE(findField(result.diagnostics, "/bumpers"), nullptr);
}

TEST(RobotProfileFile, RejectsASelfCrossingOutlineAndInvertedRanges) {
  const std::string text = R"({
  "name": "bow tie",
  "drive": {"wheel_radius_m": 0.05, "wheelbase_m": 0.3},
  "body_outline": [[0.2, 0.2], [-0.2, -0.2], [-0.2, 0.2], [0.2, -0.2]],
  "sonars": [{"x_m": 0, "y_m": 0, "heading_deg": 0, "min_range_m": 2, "max_range_m": 1}]
})";
  const auto result = parseRobotProfileJson(text, "bad.json");
  ASSERT_FALSE(result.ok());
  const Diagnostic* outline = findField(result.diagnostics, "/body_outline");
  ASSERT_NE(outline, nullptr);
  EXPECT_THAT(outline->message, HasSubstr("crosses itself"));
  EXPECT_NE(findField(result.diagnostics, "/sonars/0/max_range_m"), nullptr);
}

TEST(RobotProfileFile, RejectsAnUnsupportedVersionAndANonObjectDocument) {
  EXPECT_FALSE(parseRobotProfileJson(R"({"format_version": 2, "name": "x"})", "v.json").ok());
  const auto array = parseRobotProfileJson("[1, 2]", "a.json");
  ASSERT_FALSE(array.ok());
  EXPECT_THAT(array.diagnostics.at(0).message, HasSubstr("object"));
  EXPECT_FALSE(parseRobotProfileJson("", "empty.json").ok());
}

TEST(RobotProfileFile, KeepsUnknownKeysWithAWarningAndWritesThemBack) {
  const auto result = parseRobotProfileJson(
      minimalProfile(", \"colour\": \"red\"", ",\n  \"vendor\": {\"serial\": 42}"), "mini.json");
  ASSERT_TRUE(result.ok());
  ASSERT_NE(findField(result.diagnostics, "/vendor"), nullptr);
  EXPECT_EQ(findField(result.diagnostics, "/vendor")->severity, Severity::kWarning);
  ASSERT_NE(findField(result.diagnostics, "/sonars/1/colour"), nullptr);
  EXPECT_EQ(result.profile->extra["vendor"]["serial"], 42);
  EXPECT_EQ(result.profile->sonars[1].extra["colour"], "red");

  const nlohmann::ordered_json saved = robotProfileToJson(*result.profile);
  EXPECT_EQ(saved["vendor"]["serial"], 42);
  EXPECT_EQ(saved["sonars"][1]["colour"], "red");
}

TEST(RobotProfileFile, RoundTripsThroughTheFileFormat) {
  const auto first = parseRobotProfileJson(minimalProfile(), "mini.json");
  ASSERT_TRUE(first.ok());
  const std::string text = formatRobotProfileJson(*first.profile);
  const auto second = parseRobotProfileJson(text, "saved.json");
  ASSERT_TRUE(second.ok()) << text;
  EXPECT_TRUE(second.diagnostics.empty());
  const RobotProfile& a = *first.profile;
  const RobotProfile& b = *second.profile;
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.body_outline, b.body_outline);
  ASSERT_EQ(a.sonars.size(), b.sonars.size());
  for (std::size_t i = 0; i < a.sonars.size(); ++i) {
    EXPECT_EQ(a.sonars[i].mount.x, b.sonars[i].mount.x);
    EXPECT_NEAR(a.sonars[i].mount.theta, b.sonars[i].mount.theta, 1e-12);
    EXPECT_NEAR(a.sonars[i].beam_width_rad, b.sonars[i].beam_width_rad, 1e-12);
  }
  EXPECT_NEAR(a.limits.max_turn_rate_radps, b.limits.max_turn_rate_radps, 1e-12);
  // Saved angles are tidy degrees.
  EXPECT_THAT(text, HasSubstr("\"heading_deg\": 90.0"));
  EXPECT_THAT(text, HasSubstr("\"beam_width_deg\": 30.0"));
}

TEST(RobotProfileFile, SavesAndLoadsAFile) {
  const auto parsed = parseRobotProfileJson(minimalProfile(), "mini.json");
  ASSERT_TRUE(parsed.ok());
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("irgs_profile_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const auto path = dir / "robot.json";
  ASSERT_FALSE(saveRobotProfileFile(*parsed.profile, path).has_value());
  const auto loaded = loadRobotProfileFile(path);
  ASSERT_TRUE(loaded.ok());
  EXPECT_EQ(loaded.profile->name, "square");
  std::filesystem::remove_all(dir);
}

TEST(RobotProfileFile, ReportsAnUnreadableFile) {
  const auto result = loadRobotProfileFile("/nonexistent/irgs/robot.json");
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.diagnostics.size(), 1u);
  EXPECT_EQ(result.diagnostics[0].file, "/nonexistent/irgs/robot.json");
}

TEST(RobotProfileFile, SurvivesHostileInputWithoutThrowing) {
  const std::vector<std::string> inputs = {"{",
                                           "null",
                                           "{\"name\": 1}",
                                           "{\"body_outline\": [[1e400, 0]]}",
                                           std::string(100000, '['),
                                           "{\"sonars\": [null, 1, {}]}",
                                           "{\"drive\": [], \"limits\": 5, \"proximity\": {}}"};
  for (const auto& input : inputs) {
    RobotProfileResult result;
    EXPECT_NO_THROW(result = parseRobotProfileJson(input, "hostile.json")) << input.substr(0, 40);
    EXPECT_FALSE(result.ok());
    EXPECT_FALSE(result.diagnostics.empty());
  }
}

}  // namespace
}  // namespace irgs
