// The irgs command line and the small pure helpers of the app.

#include "app/gui/app_options.hpp"

#include <gtest/gtest.h>

#include <QDir>
#include <QFile>
#include <QTemporaryDir>

#include "app/gui/event_format.hpp"
#include "app/gui/recent_files.hpp"

namespace irgs::gui {
namespace {

AppOptionsResult parse(QStringList args) {
  args.prepend(QStringLiteral("irgs"));
  return parseAppOptions(args);
}

TEST(AppOptions, DefaultsNeedNoArguments) {
  const AppOptionsResult r = parse({});
  ASSERT_TRUE(r.options.has_value());
  EXPECT_TRUE(r.options->map_file.isEmpty());
  EXPECT_EQ(r.options->seed, 1u);
  EXPECT_FALSE(r.options->quit_after_s.has_value());
}

TEST(AppOptions, ConnectTakesALinkUrlAndControlOptionsForScripts) {
  const AppOptionsResult r = parse({"--connect", "serial:///dev/rfcomm0?baud=38400",
                                    "--control-stdin", "--status-interval", "0.25"});
  ASSERT_TRUE(r.options.has_value()) << r.message.toStdString();
  EXPECT_EQ(r.options->connect_url, QStringLiteral("serial:///dev/rfcomm0?baud=38400"));
  EXPECT_TRUE(r.options->control_stdin);
  EXPECT_EQ(r.options->status_interval_s, std::optional<double>(0.25));
  const AppOptionsResult plain = parse({});
  ASSERT_TRUE(plain.options.has_value());
  EXPECT_TRUE(plain.options->connect_url.isEmpty());
  EXPECT_FALSE(plain.options->control_stdin);
  EXPECT_FALSE(plain.options->status_interval_s.has_value());
}

TEST(AppOptions, ABadLinkUrlOrStatusIntervalIsAUsageError) {
  const AppOptionsResult url = parse({"--connect", "ftp://robot"});
  EXPECT_FALSE(url.options.has_value());
  EXPECT_EQ(url.exit_code, 2);
  EXPECT_TRUE(url.message.contains(QStringLiteral("--connect")));
  const AppOptionsResult interval = parse({"--status-interval", "0"});
  EXPECT_FALSE(interval.options.has_value());
  EXPECT_EQ(interval.exit_code, 2);
}

TEST(AppOptions, ParsesEveryOption) {
  const AppOptionsResult r = parse({"--map",
                                    "m.json",
                                    "--robot",
                                    "r.json",
                                    "--seed",
                                    "42",
                                    "--settings",
                                    "s.ini",
                                    "--drive-script",
                                    "d.json",
                                    "--screenshot",
                                    "o.png",
                                    "--screenshot-after",
                                    "6.5",
                                    "--quit-after",
                                    "30",
                                    "--window-size",
                                    "1400x900",
                                    "--speed",
                                    "0"});
  ASSERT_TRUE(r.options.has_value()) << r.message.toStdString();
  EXPECT_EQ(r.options->map_file, "m.json");
  EXPECT_EQ(r.options->robot_file, "r.json");
  EXPECT_EQ(r.options->seed, 42u);
  EXPECT_EQ(r.options->settings_file, "s.ini");
  EXPECT_EQ(r.options->drive_script_file, "d.json");
  EXPECT_EQ(r.options->screenshot_file, "o.png");
  EXPECT_DOUBLE_EQ(r.options->screenshot_after_s, 6.5);
  EXPECT_DOUBLE_EQ(*r.options->quit_after_s, 30.0);
  EXPECT_EQ(*r.options->window_size, QSize(1400, 900));
  EXPECT_DOUBLE_EQ(*r.options->sim_speed, 0.0);
}

TEST(AppOptions, RejectsBadValuesWithAMessageNamingTheOption) {
  for (const QStringList& args :
       {QStringList{"--seed", "abc"}, QStringList{"--seed", "-3"},
        QStringList{"--screenshot-after", "-1"}, QStringList{"--quit-after", "nan"},
        QStringList{"--window-size", "big"}, QStringList{"--speed", "-2"}, QStringList{"--map", ""},
        QStringList{"--bogus"}, QStringList{"stray.json"}}) {
    const AppOptionsResult r = parse(args);
    EXPECT_FALSE(r.options.has_value()) << args.join(' ').toStdString();
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_FALSE(r.message.isEmpty());
  }
  EXPECT_TRUE(parse({"--seed", "abc"}).message.contains("--seed"));
  EXPECT_TRUE(parse({"stray.json"}).message.contains("--map stray.json"));
}

TEST(AppOptions, LocalizeTakesEveryEstimatorName) {
  for (const char* name : {"ekf", "dr", "encoder-gyro", "mouse", "ekf-caster"}) {
    const AppOptionsResult r = parse({"--localize", name});
    ASSERT_TRUE(r.options.has_value()) << name << ": " << r.message.toStdString();
    EXPECT_EQ(r.options->localize, QString::fromLatin1(name));
  }
  const AppOptionsResult bad = parse({"--localize", "kalman"});
  EXPECT_FALSE(bad.options.has_value());
  EXPECT_TRUE(bad.message.contains("ekf-caster")) << bad.message.toStdString();
}

TEST(AppOptions, HelpIsNotAnError) {
  const AppOptionsResult r = parse({"--help"});
  EXPECT_FALSE(r.options.has_value());
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.message.contains("--drive-script"));
}

TEST(RecentFiles, NewestFirstWithoutDuplicatesAndBounded) {
  QStringList recent;
  for (int i = 0; i < 10; ++i)
    recent = addRecentFile(recent, QStringLiteral("/maps/m%1.json").arg(i));
  EXPECT_EQ(recent.size(), kMaxRecentFiles);
  EXPECT_EQ(recent.first(), "/maps/m9.json");
  recent = addRecentFile(recent, QStringLiteral("/maps/m5.json"));
  EXPECT_EQ(recent.first(), "/maps/m5.json");
  EXPECT_EQ(recent.count("/maps/m5.json"), 1);
}

TEST(RecentFiles, PruningDropsMissingFiles) {
  QTemporaryDir dir;
  const QString present = dir.filePath(QStringLiteral("here.json"));
  QFile file(present);
  ASSERT_TRUE(file.open(QIODevice::WriteOnly));
  file.close();
  const QStringList pruned =
      pruneRecentFiles({dir.filePath(QStringLiteral("gone.json")), present, present});
  EXPECT_EQ(pruned, QStringList{present});
}

TEST(EventFormat, PoseLineUsesMetresAndDegrees) {
  TelemetrySample sample;
  sample.odometry_pose = {1.234, -0.5, kPi / 2.0};
  sample.measured_velocity = {0.2, degToRad(15.0)};
  const QString line = formatPoseLine(sample);
  EXPECT_EQ(line, QStringLiteral("(1.23, -0.50) m 90.0°  v 0.20 m/s  ω 15°/s"));
  sample.odometry_pose = {-0.001, 0.0, -kPi};
  sample.measured_velocity = {-0.001, -0.001};
  EXPECT_EQ(formatPoseLine(sample), QStringLiteral("(0.00, 0.00) m 180.0°  v 0.00 m/s  ω 0°/s"));
}

TEST(EventFormat, SonarLineShowsCentimetresNoEchoAndNotYetFired) {
  RobotProfile profile;
  profile.sonars.resize(3);
  profile.sonars[1].max_range_m = 4.0;
  std::vector<std::optional<SonarReading>> latest(3);
  latest[0] = SonarReading{0, 1.234, true};
  latest[1] = SonarReading{1, 0.0, false};
  EXPECT_EQ(formatSonarLine(profile, latest), QStringLiteral("sonar cm 123 >400 —"));
  profile.sonars[0].name = "front";
  EXPECT_TRUE(formatSonarLegend(profile).contains(QStringLiteral("0 front, 1 (unnamed)")));
}

TEST(EventFormat, BumperChangesNameEachBumper) {
  RobotProfile profile;
  profile.bumpers.resize(2);
  profile.bumpers[0].name = "front";
  const auto lines = describeBumperChanges(profile, 0b01, 0b10);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "Bumper front released");
  EXPECT_EQ(lines[1], "Bumper #1 pressed");
}

}  // namespace
}  // namespace irgs::gui
