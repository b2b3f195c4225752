#include "core/sim/drive_script.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/geometry/types.hpp"

namespace irgs {
namespace {

using ::testing::HasSubstr;

TEST(DriveScript, ParsesCommandsCommentsAndBlankLines) {
  const auto result = parseDriveScript(
      "# warm up\n"
      "\n"
      "0.0  drive 0.2 0      # straight\n"
      "5    drive 0.1 -30\r\n"
      "12.5 stop\n",
      "teleop.txt");
  ASSERT_TRUE(result.ok());
  EXPECT_TRUE(result.diagnostics.empty());
  const DriveScript& script = *result.script;
  ASSERT_EQ(script.steps().size(), 3u);
  EXPECT_EQ(script.steps()[1].line, 4);
  EXPECT_DOUBLE_EQ(script.steps()[1].command.angular_radps, degToRad(-30.0));
  EXPECT_DOUBLE_EQ(script.lastTime_s(), 12.5);
}

TEST(DriveScript, CommandAtHoldsEachCommandUntilTheNextTime) {
  const auto result = parseDriveScript("1 drive 0.2 0\n3 drive 0 90\n3 drive 0.1 0\n6 stop\n", "s");
  ASSERT_TRUE(result.ok());
  const DriveScript& s = *result.script;
  EXPECT_EQ(s.commandAt(0.5), VelocityCommand{});  // before the first line: stopped
  EXPECT_EQ(s.commandAt(1.0), (VelocityCommand{0.2, 0.0}));
  EXPECT_EQ(s.commandAt(2.999), (VelocityCommand{0.2, 0.0}));
  EXPECT_EQ(s.commandAt(3.0), (VelocityCommand{0.1, 0.0}));  // same time: the later line wins
  EXPECT_EQ(s.commandAt(6.0), VelocityCommand{});
  EXPECT_EQ(s.commandAt(1e9), VelocityCommand{});
  EXPECT_EQ(DriveScript().commandAt(1.0), VelocityCommand{});
}

TEST(DriveScript, ReportsEachBadLineWithLineAndColumn) {
  const auto result = parseDriveScript(
      "0 drive 0.2 0\n"
      "x drive 0.2 0\n"     // 2: bad time
      "1 fly 3\n"           // 3: unknown command
      "2 drive 0.2\n"       // 4: missing argument
      "3 drive 0.2 fast\n"  // 5: bad number
      "4 stop now\n"        // 6: extra argument
      "5 stop\n"            // 7: fine
      "4.5 stop\n"          // 8: time goes back
      "-1 stop\n"           // 9: negative
      "9\n"                 // 10: no command
      "10 drive nan 0\n",   // 11: not finite
      "bad.txt");
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.diagnostics.size(), 9u);
  const std::vector<int> lines = {2, 3, 4, 5, 6, 8, 9, 10, 11};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(result.diagnostics[i].line, lines[i]);
    EXPECT_EQ(result.diagnostics[i].file, "bad.txt");
    EXPECT_GT(result.diagnostics[i].column, 0);
  }
  EXPECT_THAT(result.diagnostics[1].message, HasSubstr("unknown command \"fly\""));
  EXPECT_EQ(result.diagnostics[1].column, 3);
  EXPECT_EQ(result.diagnostics[3].column, 13);  // "fast"
  EXPECT_THAT(result.diagnostics[5].message, HasSubstr("earlier"));
  EXPECT_THAT(result.diagnostics[3].toString(), HasSubstr("bad.txt:5:13: error:"));
}

TEST(DriveScript, AnEmptyTextIsAnEmptyScript) {
  const auto result = parseDriveScript("# nothing\n\n", "empty.txt");
  ASSERT_TRUE(result.ok());
  EXPECT_TRUE(result.script->empty());
}

TEST(DriveScript, ConstructorRejectsDecreasingTimes) {
  EXPECT_THROW(DriveScript({{2.0, {}, 0}, {1.0, {}, 0}}), std::invalid_argument);
  EXPECT_THROW(DriveScript({{-1.0, {}, 0}}), std::invalid_argument);
}

TEST(DriveScript, ReportsAMissingFile) {
  const auto result = loadDriveScriptFile("/nonexistent/irgs/script.txt");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.diagnostics.size(), 1u);
}

}  // namespace
}  // namespace irgs
