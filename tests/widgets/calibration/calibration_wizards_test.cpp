// The calibration wizards end to end, offscreen: the user's clicks run the procedure in the
// simulator, the wizard writes the corrected profile, and the written file carries corrections
// within 10 % of the injected errors (issue 6 acceptance, through the GUI).

#include <gtest/gtest.h>

#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QtTest/QTest>
#include <filesystem>
#include <fstream>

#include "core/calibration/profile_calibration.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "widgets/calibration/gyro_wizard.hpp"
#include "widgets/calibration/umbmark_wizard.hpp"

namespace irgs::widgets {
namespace {

RobotProfile p3dx() {
  const RobotProfileResult r = loadRobotProfileFile(std::filesystem::path(IRGS_SOURCE_DIR) /
                                                    "resources/robots/pioneer_p3dx.json");
  if (!r.ok())
    throw std::runtime_error("cannot load the P3-DX profile");
  return *r.profile;
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "irgs_calibration_wizards_test";
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir / name);
  return dir / name;
}

QPushButton* button(QWidget& parent, const char* name) {
  auto* b = parent.findChild<QPushButton*>(QString::fromLatin1(name));
  if (b == nullptr)
    throw std::runtime_error(std::string("no button ") + name);
  return b;
}

TEST(UmbmarkWizard, TheSimulatedRunRecoversTheInjectedErrorsAndWritesTheProfile) {
  const RobotProfile robot = p3dx();
  const auto out = scratch("p3dx_umbmark.json");
  UmbmarkWizard wizard(robot, QString::fromStdString(out.string()));
  wizard.show();
  UmbmarkInjection injection;
  injection.wheel_diameter_ratio = 1.01;
  injection.wheelbase_scale = 1.03;
  injection.slip_stddev = 0.002;
  wizard.setInjection(injection);
  wizard.setRunsPerDirection(5);
  wizard.setSeed(11);
  QPushButton* write = button(wizard, "umbmarkWriteProfile");
  EXPECT_FALSE(write->isEnabled());  // nothing to write yet
  QTest::mouseClick(button(wizard, "umbmarkRunSimulation"), Qt::LeftButton);
  ASSERT_TRUE(wizard.result().has_value());
  ASSERT_TRUE(wizard.result()->ok) << wizard.resultText().toStdString();
  EXPECT_GE(wizard.result()->improvement(), 5.0) << wizard.resultText().toStdString();
  EXPECT_TRUE(wizard.resultText().contains(QStringLiteral("better")));
  ASSERT_TRUE(write->isEnabled());
  QSignalSpy written(&wizard, &UmbmarkWizard::profileWritten);
  QTest::mouseClick(write, Qt::LeftButton);
  ASSERT_EQ(written.count(), 1);

  const RobotProfileResult loaded = loadRobotProfileFile(out);
  ASSERT_TRUE(loaded.ok());
  const ProfileOdometry odo = profileOdometry(*loaded.profile);
  ASSERT_TRUE(odo.error.empty());
  const double e_d = odo.odometry.right_wheel_scale / odo.odometry.left_wheel_scale;
  EXPECT_LT(std::abs(e_d - 1.01), 0.1 * 0.01) << e_d;
  const double e_b = loaded.profile->drive.wheelbase_m / robot.drive.wheelbase_m;
  EXPECT_LT(std::abs(e_b - 1.03), 0.1 * 0.03) << e_b;
}

TEST(UmbmarkWizard, RobotRunsAskTheApplicationToDriveAndAnalyseTheMeasuredEnds) {
  const RobotProfile robot = p3dx();
  const auto out = scratch("p3dx_robot_umbmark.json");
  UmbmarkWizard wizard(robot, QString::fromStdString(out.string()));
  wizard.setSource(UmbmarkWizard::Source::kRobot);
  wizard.show();
  QSignalSpy requested(&wizard, &UmbmarkWizard::driveSquareRequested);
  QTest::mouseClick(button(wizard, "umbmarkDriveCw"), Qt::LeftButton);
  ASSERT_EQ(requested.count(), 1);
  const auto config = requested.takeFirst().at(0).value<UmbmarkSquareConfig>();
  EXPECT_EQ(config.direction, UmbmarkDirection::kClockwise);
  EXPECT_DOUBLE_EQ(config.side_m, 4.0);
  EXPECT_FALSE(button(wizard, "umbmarkDriveCcw")->isEnabled());  // one square at a time

  // The application reports the runs; the first is measured by hand (typed into the table).
  wizard.addRobotRun(UmbmarkDirection::kClockwise, Vec2(0.001, -0.0005), std::nullopt);
  EXPECT_TRUE(button(wizard, "umbmarkDriveCcw")->isEnabled());
  auto* table = wizard.findChild<QTableWidget*>(QStringLiteral("umbmarkRuns"));
  ASSERT_NE(table, nullptr);
  table->item(0, 3)->setText(QStringLiteral("0.311"));
  table->item(0, 4)->setText(QStringLiteral("-0.8605"));
  wizard.addRobotRun(UmbmarkDirection::kCounterClockwise, Vec2(0.0, 0.0), Vec2(0.33, 0.86));
  EXPECT_EQ(table->item(1, 3)->text(), QStringLiteral("0.3300"));  // the truth, pre-filled
  QTest::mouseClick(button(wizard, "umbmarkAnalyse"), Qt::LeftButton);
  ASSERT_TRUE(wizard.result().has_value());
  ASSERT_TRUE(wizard.result()->ok) << wizard.resultText().toStdString();
  EXPECT_EQ(wizard.result()->runs.size(), 2u);
  EXPECT_NEAR(wizard.result()->runs[0].error_m.x(), 0.310, 1e-9);
  EXPECT_FALSE(wizard.result()->verification.has_value());  // no truth to re-run against
  ASSERT_TRUE(wizard.writeProfile());
  EXPECT_TRUE(loadRobotProfileFile(out).ok());

  // A missing measurement is reported, the run is left out.
  wizard.addRobotRun(UmbmarkDirection::kClockwise, Vec2(0.0, 0.0), std::nullopt);
  wizard.analyseRobotRuns();
  EXPECT_TRUE(wizard.resultText().contains(QStringLiteral("run 3")));
  EXPECT_EQ(wizard.result()->runs.size(), 2u);
}

TEST(UmbmarkWizard, AnUnwritableOutputIsReportedNotThrown) {
  UmbmarkWizard wizard(p3dx(), QStringLiteral("/proc/irgs_no_such_dir/p.json"));
  wizard.setRunsPerDirection(1);
  wizard.runSimulation();
  ASSERT_TRUE(wizard.result() && wizard.result()->ok);
  EXPECT_FALSE(wizard.writeProfile());
}

TEST(GyroWizard, TheSimulatedCalibrationRecoversTheInjectedCoefficientsAndWritesTheProfile) {
  const auto out = scratch("p3dx_gyro.json");
  GyroWizard wizard(p3dx(), QString::fromStdString(out.string()));
  wizard.show();
  wizard.setSeed(5);
  QTest::mouseClick(button(wizard, "gyroRun"), Qt::LeftButton);
  ASSERT_TRUE(wizard.result().has_value());
  ASSERT_TRUE(wizard.result()->ok) << wizard.statusText().toStdString();
  QTableWidget* table = wizard.resultsTable();
  ASSERT_GE(table->rowCount(), 5);
  for (int row = 0; row < table->rowCount(); ++row) {
    const QString name = table->item(row, 0)->text();
    if (name == QStringLiteral("c0"))
      continue;  // an extrapolation to 0 C, outside the chamber's range (docs/calibration.md)
    EXPECT_LT(table->item(row, 3)->text().toDouble(), 10.0) << name.toStdString();
  }
  QTest::mouseClick(button(wizard, "gyroWriteProfile"), Qt::LeftButton);
  const RobotProfileResult loaded = loadRobotProfileFile(out);
  ASSERT_TRUE(loaded.ok());
  const std::optional<GyroCalibration> c = profileGyroCalibration(*loaded.profile);
  ASSERT_TRUE(c.has_value());
  const GyroErrorModel injected = autogyroErrorModel();
  EXPECT_NEAR(c->scale.a1, injected.sf_a1, 0.1 * injected.sf_a1);
  EXPECT_NEAR(c->scale.a3_per_dps2, injected.sf_a3_per_dps2, 0.1 * injected.sf_a3_per_dps2);
  EXPECT_NEAR(c->bias.c1_dps_per_c, injected.bias_c1_dps_per_c, 0.1 * injected.bias_c1_dps_per_c);
}

TEST(GyroWizard, LogsFromTheRobotAreFittedAndAMissingFileIsReported) {
  const auto rate = scratch("rate.csv");
  const auto rest = scratch("rest.csv");
  {
    // A gyro with a1 = 0.01, no curvature, bias 0.02 + 0.001 T: true - indicated = 0.01 x + bias.
    std::ofstream r(rate);
    r << "true_dps,indicated_dps\n";
    for (int w = -90; w <= 90; w += 10) {
      const double x = (w + 0.045) / 1.01;  // the table at 25 C: bias 0.045 deg/s
      r << w << ',' << x << '\n';
    }
    std::ofstream s(rest);
    s << "temperature_c,indicated_dps\n";
    for (int t = 15; t <= 40; ++t) {
      const double b = 0.02 + 0.001 * t;
      s << t << ',' << b / 1.01 << '\n';  // x + 0.01 x = b
    }
  }
  GyroWizard wizard(p3dx(), QString::fromStdString(scratch("p3dx_logs.json").string()));
  wizard.setSource(GyroWizard::Source::kLogs);
  wizard.setLogFiles(QString::fromStdString(rate.string()), QString::fromStdString(rest.string()));
  wizard.run();
  ASSERT_TRUE(wizard.result() && wizard.result()->ok) << wizard.statusText().toStdString();
  EXPECT_NEAR(wizard.result()->calibration.scale.a1, 0.01, 1e-6);
  EXPECT_NEAR(wizard.result()->calibration.bias.c1_dps_per_c, 0.001, 1e-6);
  EXPECT_TRUE(wizard.writeProfile());

  wizard.setLogFiles(QStringLiteral("/no/such/rate.csv"), QString::fromStdString(rest.string()));
  wizard.run();
  EXPECT_FALSE(wizard.result().has_value());
  EXPECT_TRUE(wizard.statusText().contains(QStringLiteral("/no/such/rate.csv")));
}

}  // namespace
}  // namespace irgs::widgets
