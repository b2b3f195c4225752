// TelemetryAssembler, pure: frames from a real FirmwareCore (encoded, decoded) and hand-built
// frames; no threads, no clock. Frame conventions are checked against what the firmware had.

#include "comms/robot/telemetry_assembler.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/robot/linked_robot.hpp"
#include "core/estimation/estimator_runner.hpp"
#include "tests/comms/link/link_test_support.hpp"
#include "tests/comms/robot/robot_test_support.hpp"

namespace irgs::comms {
namespace {

namespace mav = mavlink;
using testing::frameOf;

constexpr double kFloatTol = 2e-6;  // metres / radians: float precision over a few metres

// Runs the firmware for `seconds` of robot time while a ground station (heartbeats, MANUAL_CONTROL
// every 0.1 s) drives it with `x`, `r`, and feeds every frame it emits to `assembler`. Returns
// the firmware's odometry pose at the end of each step, by boot time in ms, and the sonar frames.
struct FirmwareRun {
  std::map<std::int64_t, Pose2> odometry;
  std::map<std::int64_t, std::vector<mav::DistanceSensor>> sonar;
};

FirmwareRun runFirmware(app::FirmwareCore& fw, TelemetryAssembler& assembler, double seconds,
                        std::int16_t x, std::int16_t r) {
  FirmwareRun run;
  mav::FrameDecoder decoder;
  std::vector<mav::Frame> frames;
  mav::Heartbeat hb;
  hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
  mav::ManualControl mc;
  mc.x = x;
  mc.r = r;
  const double dt = fw.simulator().config().dt_s;
  const int steps = static_cast<int>(std::lround(seconds / dt));
  for (int i = 0; i < steps; ++i) {
    const double t = fw.simulator().time_s();
    if (i % 50 == 0)
      fw.receive(frameOf(hb, 255, 190), t);
    if (i % 10 == 0)
      fw.receive(frameOf(mc, 255, 190), t);
    fw.advance(t + dt);
    const auto ms = std::llround(fw.simulator().time_s() * 1000.0);
    run.odometry[ms] = fw.simulator().odometryPose();
    frames.clear();
    decoder.feed(fw.takeOutput(), frames);
    for (const auto& f : frames) {
      if (const auto ds = f.as<mav::DistanceSensor>())
        run.sonar[ds->time_boot_ms].push_back(*ds);
      assembler.onFrame(f, fw.simulator().time_s());
    }
    assembler.tick(fw.simulator().time_s());
  }
  return run;
}

void expectPosesMatch(const std::vector<TelemetrySample>& samples, const FirmwareRun& run) {
  for (const auto& s : samples) {
    const auto it = run.odometry.find(std::llround(s.time_s * 1000.0));
    ASSERT_NE(it, run.odometry.end()) << "no firmware step at " << s.time_s;
    EXPECT_NEAR(s.odometry_pose.x, it->second.x, kFloatTol) << s.time_s;
    EXPECT_NEAR(s.odometry_pose.y, it->second.y, kFloatTol) << s.time_s;
    EXPECT_NEAR(wrapAngle(s.odometry_pose.theta - it->second.theta), 0.0, kFloatTol) << s.time_s;
    EXPECT_FALSE(s.true_pose.has_value());
  }
}

TEST(TelemetryAssembler, FullStreamGivesTheFirmwareOdometryAtTwentyHertzWithItsSonar) {
  auto fw = testing::makeFirmware();
  TelemetryAssembler assembler(testing::thesisRobot());
  // Forward and turning right (r > 0 is clockwise): theta must decrease.
  const FirmwareRun run = runFirmware(*fw, assembler, 3.0, 600, 300);
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 58u);                   // 3 s at 20 Hz, the last one still held
  for (std::size_t i = 2; i < samples.size(); ++i)  // the first pose is at the first step
    EXPECT_NEAR(samples[i].time_s - samples[i - 1].time_s, 0.05, 1e-9);
  expectPosesMatch(samples, run);
  EXPECT_GT(samples.back().odometry_pose.x - samples.front().odometry_pose.x, 0.2);
  EXPECT_LT(wrapAngle(samples.back().odometry_pose.theta - samples.front().odometry_pose.theta),
            -0.3);
  EXPECT_GT(samples.back().measured_velocity.linear_mps, 0.1);
  EXPECT_LT(samples.back().measured_velocity.angular_radps, -0.1);
  EXPECT_GT(samples.back().left_ticks, samples.back().right_ticks);  // turning right

  // Every sample carries exactly the DISTANCE_SENSOR frames of its own time stamp.
  const RobotProfile profile = testing::thesisRobot();
  std::vector<int> per_sensor(profile.sonars.size(), 0);
  for (const auto& s : samples) {
    const auto it = run.sonar.find(std::llround(s.time_s * 1000.0));
    const std::size_t expected = it == run.sonar.end() ? 0 : it->second.size();
    ASSERT_EQ(s.sonar.size(), expected) << s.time_s;
    for (std::size_t i = 0; i < expected; ++i) {
      const auto& ds = it->second[i];
      const SonarReading& r = s.sonar[i];
      EXPECT_EQ(r.sensor, ds.id);
      EXPECT_EQ(r.echo, ds.current_distance <= ds.max_distance);
      if (r.echo) {
        EXPECT_DOUBLE_EQ(r.range_m, ds.current_distance * 0.01);
      }
      ++per_sensor[static_cast<std::size_t>(r.sensor)];
      // The index is the profile's: the frame's orientation is that sonar's mount (CW steps).
      const double cw_deg =
          -radToDeg(profile.sonars[static_cast<std::size_t>(r.sensor)].mount.theta);
      const double steps = std::round(cw_deg / 45.0);
      if (std::abs(cw_deg - steps * 45.0) <= 1.0) {
        EXPECT_EQ(ds.orientation, ((static_cast<int>(steps) % 8) + 8) % 8);
      }
    }
  }
  for (std::size_t i = 0; i < per_sensor.size(); ++i)
    EXPECT_GE(per_sensor[i], 20) << "sonar " << i;
  EXPECT_EQ(assembler.counters().ignored_readings, 0u);
}

TEST(TelemetryAssembler, OdometryMessageAloneGivesTheSamePoses) {
  app::FirmwareConfig config;
  config.send_local_position = false;
  auto fw = testing::makeFirmware(config);
  TelemetryAssembler assembler(testing::thesisRobot());
  const FirmwareRun run = runFirmware(*fw, assembler, 2.0, -400, -500);  // back, turning left
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 38u);
  expectPosesMatch(samples, run);
  EXPECT_LT(samples.back().measured_velocity.linear_mps, -0.05);
  EXPECT_GT(samples.back().measured_velocity.angular_radps, 0.1);
}

TEST(TelemetryAssembler, SlowLinkProfileUsesPose2dAndSonarScan) {
  auto fw = testing::makeFirmware(app::slowLinkFirmwareConfig());
  TelemetryAssembler assembler(testing::thesisRobot());
  const FirmwareRun run = runFirmware(*fw, assembler, 3.0, 500, 0);
  EXPECT_TRUE(run.sonar.empty());  // no DISTANCE_SENSOR in the compact profile
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 28u);  // 10 Hz
  expectPosesMatch(samples, run);
  std::size_t readings = 0;
  std::vector<bool> seen(testing::thesisRobot().sonars.size(), false);
  for (const auto& s : samples) {
    for (const auto& r : s.sonar) {
      ASSERT_GE(r.sensor, 0);
      ASSERT_LT(static_cast<std::size_t>(r.sensor), seen.size());
      seen[static_cast<std::size_t>(r.sensor)] = true;
      if (r.echo) {
        EXPECT_GT(r.range_m, 0.0);
      }
    }
    readings += s.sonar.size();
  }
  EXPECT_GE(readings, 8u * 10u);
  for (std::size_t i = 0; i < seen.size(); ++i)
    EXPECT_TRUE(seen[i]) << "sonar " << i;
}

// ---- hand-built frames ----

mav::Frame lpn(std::uint32_t ms, float x, float y_ned) {
  mav::LocalPositionNed m;
  m.time_boot_ms = ms;
  m.x = x;
  m.y = y_ned;
  return frameOf(m);
}

mav::Frame att(std::uint32_t ms, float yaw_ned) {
  mav::Attitude m;
  m.time_boot_ms = ms;
  m.yaw = yaw_ned;
  return frameOf(m);
}

mav::Frame ds(std::uint32_t ms, std::uint8_t id, std::uint16_t cm, std::uint16_t max_cm = 400) {
  mav::DistanceSensor m;
  m.time_boot_ms = ms;
  m.id = id;
  m.current_distance = cm;
  m.min_distance = 3;
  m.max_distance = max_cm;
  return frameOf(m);
}

TEST(TelemetryAssembler, NedPoseIsConvertedToOurFrame) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(lpn(100, 1.5f, 0.25f), 0.0);
  assembler.onFrame(att(100, 0.5f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_DOUBLE_EQ(samples[0].time_s, 0.1);
  EXPECT_NEAR(samples[0].odometry_pose.x, 1.5, 1e-7);
  EXPECT_NEAR(samples[0].odometry_pose.y, -0.25, 1e-7);     // NED y is to the right
  EXPECT_NEAR(samples[0].odometry_pose.theta, -0.5, 1e-7);  // NED yaw is clockwise
}

TEST(TelemetryAssembler, ByTimestampHoldsASampleForItsSonarUntilNewerDataOrTheHoldTime) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.hold_s = 0.1});
  assembler.onFrame(lpn(100, 1.0f, 0.0f), 10.0);
  assembler.onFrame(att(100, 0.0f), 10.0);
  assembler.onFrame(ds(100, 2, 150), 10.01);
  EXPECT_FALSE(assembler.hasReady());
  assembler.onFrame(lpn(150, 1.1f, 0.0f), 10.05);  // next step: 100 is complete
  auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 1u);
  ASSERT_EQ(samples[0].sonar.size(), 1u);
  EXPECT_EQ(samples[0].sonar[0].sensor, 2);
  EXPECT_TRUE(samples[0].sonar[0].echo);
  EXPECT_DOUBLE_EQ(samples[0].sonar[0].range_m, 1.5);

  assembler.onFrame(att(150, 0.0f), 10.05);
  assembler.onFrame(ds(150, 3, 401), 10.06);  // beyond max_distance: no echo
  assembler.tick(10.1);
  EXPECT_FALSE(assembler.hasReady());
  assembler.tick(10.16);  // nothing newer for hold_s
  samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_DOUBLE_EQ(samples[0].odometry_pose.x, static_cast<double>(1.1f));
  ASSERT_EQ(samples[0].sonar.size(), 1u);
  EXPECT_FALSE(samples[0].sonar[0].echo);
  EXPECT_DOUBLE_EQ(samples[0].sonar[0].range_m, testing::thesisRobot().sonars[3].max_range_m);
}

TEST(TelemetryAssembler, ReleaseOnPoseCarriesLateReadingsToTheNextSample) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(lpn(100, 1.0f, 0.0f), 0.0);
  EXPECT_FALSE(assembler.hasReady());  // no heading yet
  assembler.onFrame(att(100, 0.0f), 0.0);
  EXPECT_EQ(assembler.takeReady().size(), 1u);
  assembler.onFrame(ds(100, 1, 80), 0.0);
  assembler.onFrame(lpn(100, 1.0f, 0.0f), 0.0);  // a duplicate pose of a released sample
  EXPECT_EQ(assembler.counters().stale_poses, 1u);
  assembler.onFrame(lpn(150, 1.2f, 0.0f), 0.0);
  assembler.onFrame(att(150, 0.0f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_DOUBLE_EQ(samples[0].time_s, 0.15);
  ASSERT_EQ(samples[0].sonar.size(), 1u);
  EXPECT_EQ(samples[0].sonar[0].sensor, 1);
}

TEST(TelemetryAssembler, TheFirstCompletePoseOfAStepWinsWhateverTheHoldTimerDid) {
  // The same step's pose arrives twice, rounded differently (as ODOMETRY's quaternion and
  // ATTITUDE's yaw do). Whether the hold timer released the sample between the two copies
  // (a loaded live run) or not (its replay) must not change the sample.
  const auto feed = [](bool hold_fires_between) {
    TelemetryAssembler assembler(testing::thesisRobot(), {.hold_s = 0.1});
    assembler.onFrame(lpn(100, 1.0f, 0.0f), 10.0);
    assembler.onFrame(att(100, 0.5f), 10.0);
    if (hold_fires_between)
      assembler.tick(10.2);
    assembler.onFrame(lpn(100, 1.0000001f, 0.0f), 10.21);
    assembler.onFrame(att(100, 0.5000001f), 10.21);
    assembler.onFrame(lpn(150, 1.1f, 0.0f), 10.25);
    auto samples = assembler.takeReady();
    EXPECT_EQ(samples.size(), 1u);
    EXPECT_EQ(assembler.counters().stale_poses + assembler.counters().duplicate_poses, 2u);
    return samples.empty() ? Pose2{} : samples[0].odometry_pose;
  };
  const Pose2 loaded = feed(true);
  const Pose2 replayed = feed(false);
  EXPECT_EQ(loaded.x, static_cast<double>(1.0f));
  EXPECT_EQ(replayed.x, loaded.x);
  EXPECT_EQ(replayed.y, loaded.y);
  EXPECT_EQ(replayed.theta, loaded.theta);
}

TEST(TelemetryAssembler, ReadingsAfterAHoldReleaseRideOnTheirOwnStepsPose) {
  // Live under load the hold timer may release step 100 before its sonar readings arrive; a
  // replay of the same bytes does not. Every reading must meet the same pose either way.
  struct Ride {
    double time_s, x;
    int sensor;
    double range_m;
    bool operator==(const Ride&) const = default;
  };
  const auto feed = [](bool hold_fires_early) {
    TelemetryAssembler assembler(testing::thesisRobot(), {.hold_s = 0.1});
    std::vector<TelemetrySample> samples;
    const auto take = [&] {
      for (auto& s : assembler.takeReady())
        samples.push_back(std::move(s));
    };
    assembler.onFrame(lpn(100, 1.0f, 0.0f), 10.0);
    assembler.onFrame(att(100, 0.0f), 10.0);
    assembler.onFrame(ds(100, 1, 120), 10.01);
    if (hold_fires_early) {
      assembler.tick(10.2);
      take();  // the owner took the held sample before the rest of its readings came
    }
    assembler.onFrame(ds(100, 2, 150), 10.21);
    assembler.onFrame(ds(100, 3, 180), 10.21);
    assembler.tick(10.22);
    take();
    assembler.onFrame(lpn(150, 1.1f, 0.0f), 10.25);
    assembler.onFrame(att(150, 0.0f), 10.25);
    assembler.onFrame(ds(150, 4, 90), 10.26);
    assembler.onFrame(lpn(200, 1.2f, 0.0f), 10.3);
    take();
    std::vector<Ride> rides;
    for (const auto& s : samples)
      for (const auto& r : s.sonar)
        rides.push_back({s.time_s, s.odometry_pose.x, r.sensor, r.range_m});
    return std::pair{rides, assembler.counters().late_samples};
  };
  const auto [loaded, late_loaded] = feed(true);
  const auto [replayed, late_replayed] = feed(false);
  ASSERT_EQ(loaded.size(), 4u);
  EXPECT_EQ(loaded, replayed);
  EXPECT_EQ(late_loaded, 1u) << "the late readings should have left in one supplementary sample";
  EXPECT_EQ(late_replayed, 0u);
  EXPECT_EQ(loaded[1].time_s, 0.1);
  EXPECT_EQ(loaded[1].x, static_cast<double>(1.0f));  // sensor 2 rode on step 100's pose
}

TEST(TelemetryAssembler, UnknownSensorsAndZeroRangesAreCountedNotDelivered) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(ds(100, 200, 100), 0.0);  // the thesis robot has 8 sonars
  assembler.onFrame(ds(100, 0, 0), 0.0);
  assembler.onFrame(ds(100, 0, 120), 0.0);
  assembler.onFrame(lpn(100, 0.0f, 0.0f), 0.0);
  assembler.onFrame(att(100, 0.0f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 1u);
  ASSERT_EQ(samples[0].sonar.size(), 1u);
  EXPECT_EQ(samples[0].sonar[0].sensor, 0);
  EXPECT_EQ(assembler.counters().ignored_readings, 2u);
}

TEST(TelemetryAssembler, ContactAndTicksAreCarriedToEverySample) {
  const RobotProfile profile = testing::thesisRobot();
  ASSERT_FALSE(profile.proximity.empty());
  TelemetryAssembler assembler(profile, {.release_on_pose = true});
  mav::IrgsContact contact;
  contact.time_boot_ms = 90;
  contact.bumpers = 0b101;
  contact.proximity_count = static_cast<std::uint8_t>(profile.proximity.size());
  contact.proximity.fill(std::numeric_limits<std::uint16_t>::max());
  contact.proximity[0] = 120;
  assembler.onFrame(frameOf(contact), 0.0);
  mav::IrgsEncoderTicks ticks;
  ticks.time_usec = 90'000;
  ticks.left_ticks = -12345;
  ticks.right_ticks = 678;
  assembler.onFrame(frameOf(ticks), 0.0);
  for (std::uint32_t ms : {100u, 150u}) {
    assembler.onFrame(lpn(ms, 0.0f, 0.0f), 0.0);
    assembler.onFrame(att(ms, 0.0f), 0.0);
  }
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 2u);
  for (const auto& s : samples) {
    EXPECT_EQ(s.bumpers, 0b101u);
    EXPECT_EQ(s.left_ticks, -12345);
    EXPECT_EQ(s.right_ticks, 678);
    ASSERT_EQ(s.proximity_m.size(), profile.proximity.size());
    EXPECT_DOUBLE_EQ(s.proximity_m[0], 0.12);
    if (profile.proximity.size() > 1) {
      EXPECT_DOUBLE_EQ(s.proximity_m[1], profile.proximity[1].max_range_m);
    }
  }
}

mav::Frame imu(std::uint32_t ms, std::int16_t zgyro_frd, std::int16_t cdeg) {
  mav::ScaledImu m;
  m.time_boot_ms = ms;
  m.zgyro = zgyro_frd;
  m.zacc = -1000;
  m.temperature = cdeg;
  return frameOf(m);
}

// SCALED_IMU's z rate (FRD, mrad/s) becomes the sample's gyro reading (ours: z up, rad/s) and
// rides on every sample while it is fresh, so the encoder + gyro filter has its sensor over the
// link; a stream that stopped is not taken for a gyro at rest.
TEST(TelemetryAssembler, ScaledImuYawRateBecomesTheGyroReadingOfEverySampleWhileFresh) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(lpn(50, 0.0f, 0.0f), 0.0);
  assembler.onFrame(att(50, 0.0f), 0.0);  // before any IMU frame: no gyro
  assembler.onFrame(imu(100, -250, 3150), 0.0);
  for (std::uint32_t ms : {100u, 150u, 400u, 450u}) {
    assembler.onFrame(lpn(ms, 0.0f, 0.0f), 0.0);
    assembler.onFrame(att(ms, 0.0f), 0.0);
  }
  assembler.onFrame(imu(500, 32767, 0), 0.0);  // saturated, no temperature
  assembler.onFrame(lpn(500, 0.0f, 0.0f), 0.0);
  assembler.onFrame(att(500, 0.0f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 6u);
  EXPECT_FALSE(samples[0].gyro.has_value());
  for (std::size_t i : {1u, 2u, 3u}) {
    ASSERT_TRUE(samples[i].gyro.has_value()) << samples[i].time_s;
    EXPECT_DOUBLE_EQ(samples[i].gyro->rate_radps, 0.25);  // FRD -250 mrad/s: CCW, ours +
    EXPECT_DOUBLE_EQ(samples[i].gyro->temperature_c, 31.5);
    EXPECT_FALSE(samples[i].gyro->saturated);
  }
  EXPECT_FALSE(samples[4].gyro.has_value());  // 0.35 s old: stale
  ASSERT_TRUE(samples[5].gyro.has_value());
  EXPECT_TRUE(samples[5].gyro->saturated);
  EXPECT_DOUBLE_EQ(samples[5].gyro->temperature_c, 25.0);
  EXPECT_EQ(assembler.counters().gyro_readings, 2u);
  EXPECT_THROW(TelemetryAssembler(testing::thesisRobot(), {.max_gyro_age_s = -1.0}),
               std::invalid_argument);
}

// From the firmware: its simulated AUTOGYRO's raw rate and temperature arrive on the samples,
// and the rate agrees with the turn the odometry saw (bias and scale error are small).
TEST(TelemetryAssembler, TheFirmwaresGyroArrivesOnTheSamplesAndFollowsTheTurn) {
  SimConfig sim;
  sim.seed = 7;
  sim = typicalSimConfig(sim);
  sim.gyro = autogyroErrorModel();
  app::FirmwareCore fw(Simulator(testing::defaultMap(), testing::thesisRobot(), sim), {});
  TelemetryAssembler assembler(testing::thesisRobot());
  runFirmware(fw, assembler, 4.0, 0, -400);  // turn on the spot, counter-clockwise
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 70u);
  std::size_t with_gyro = 0;
  double rate_sum = 0.0, omega_sum = 0.0;
  for (const auto& s : samples) {
    if (!s.gyro || s.time_s < 1.0)  // after the spin-up
      continue;
    ++with_gyro;
    rate_sum += s.gyro->rate_radps;
    omega_sum += s.measured_velocity.angular_radps;
    EXPECT_GT(s.gyro->temperature_c, 19.0);  // AUTOGYRO warm-up from 20 C
    EXPECT_LT(s.gyro->temperature_c, 36.0);
  }
  ASSERT_GT(with_gyro, 50u);
  const double n = static_cast<double>(with_gyro);
  EXPECT_GT(omega_sum / n, 0.2);
  // Scale-factor error ~1.3 % and bias ~0.05 deg/s, plus 1 mrad/s quantisation.
  EXPECT_NEAR(rate_sum / n, omega_sum / n, 0.03 * omega_sum / n + 0.003);

  // The encoder + gyro filter (paper 001) takes these readings as it takes the simulator's.
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kEncoderGyro;
  EstimatorRunner runner(testing::defaultMap(), testing::thesisRobot(),
                         samples.front().odometry_pose, config);
  for (const auto& s : samples)
    runner.feed(s);
  EXPECT_GT(runner.metrics().readings, 50);
  EXPECT_GT(runner.metrics().accepted, 50);
}

// IRGS_MOUSE_COUNTS and IRGS_CASTER_ENCODERS ride on every sample from the first frame on, like
// the encoder ticks; the floor-sensor state and the residual are taken as the frames say.
TEST(TelemetryAssembler, FloorSensorCountsAndCasterEncodersAreCarriedToEverySample) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(lpn(50, 0.0f, 0.0f), 0.0);
  assembler.onFrame(att(50, 0.0f), 0.0);  // before any such frame: neither
  mav::IrgsMouseCounts mouse;
  mouse.time_usec = 100'000;
  mouse.right_x = 1200;
  mouse.right_y = -35;
  mouse.left_x = 1190;
  mouse.left_y = 7;
  mouse.right_status = static_cast<std::uint8_t>(mav::IrgsMouseStatus::kSaturated);
  mouse.left_status = static_cast<std::uint8_t>(mav::IrgsMouseStatus::kTracking);
  assembler.onFrame(frameOf(mouse), 0.0);
  mav::IrgsCasterEncoders casters;
  casters.time_usec = 100'000;
  casters.drive = {27000, -13500, 5};
  casters.steering = {0, 8482, -4241};
  casters.residual_sum = 0.0725;
  casters.residual_periods = 100;
  casters.flags = static_cast<std::uint8_t>(mav::IrgsCasterFlags::kResidualValid);
  assembler.onFrame(frameOf(casters), 0.0);
  for (std::uint32_t ms : {100u, 150u}) {
    assembler.onFrame(lpn(ms, 0.0f, 0.0f), 0.0);
    assembler.onFrame(att(ms, 0.0f), 0.0);
  }
  mouse.time_usec = 200'000;
  mouse.left_status = 7;  // not an IRGS_MOUSE_STATUS: not trusted
  assembler.onFrame(frameOf(mouse), 0.0);
  casters.time_usec = 200'000;
  casters.residual_sum = 123.0;
  casters.residual_periods = 5;
  casters.flags = 0;  // the residual is not valid: not taken
  assembler.onFrame(frameOf(casters), 0.0);
  assembler.onFrame(lpn(200, 0.0f, 0.0f), 0.0);
  assembler.onFrame(att(200, 0.0f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 4u);
  EXPECT_FALSE(samples[0].mouse.has_value());
  EXPECT_FALSE(samples[0].casters.has_value());
  for (std::size_t i : {1u, 2u}) {
    ASSERT_TRUE(samples[i].mouse.has_value());
    EXPECT_EQ(samples[i].mouse->right.dx, 1200);
    EXPECT_EQ(samples[i].mouse->right.dy, -35);
    EXPECT_EQ(samples[i].mouse->left.dx, 1190);
    EXPECT_EQ(samples[i].mouse->left.dy, 7);
    EXPECT_EQ(samples[i].mouse->right.status, MouseStatus::kSaturated);
    EXPECT_EQ(samples[i].mouse->left.status, MouseStatus::kTracking);
    ASSERT_TRUE(samples[i].casters.has_value());
    const CasterEncoders& c = *samples[i].casters;
    EXPECT_EQ(c.drive_ticks, (std::array<std::int64_t, 3>{27000, -13500, 5}));
    EXPECT_EQ(c.steering_ticks, (std::array<std::int64_t, 3>{0, 8482, -4241}));
    EXPECT_DOUBLE_EQ(c.residual_sum_rad, 0.0725);
    EXPECT_EQ(c.residual_periods, 100);
  }
  ASSERT_TRUE(samples[3].mouse && samples[3].casters);
  EXPECT_EQ(samples[3].mouse->left.status, MouseStatus::kLifted);
  EXPECT_EQ(samples[3].casters->residual_periods, 0);
  EXPECT_EQ(samples[3].casters->residual_sum_rad, 0.0);
  EXPECT_EQ(assembler.counters().mouse_frames, 2u);
  EXPECT_EQ(assembler.counters().caster_frames, 2u);
}

// Runs `fw` for `seconds` with a ground station driving it (x, r as MANUAL_CONTROL), feeding
// every frame to `assembler`; returns the simulator's true pose at each step by boot time in ms.
std::map<std::int64_t, Pose2> runWithTruth(app::FirmwareCore& fw, TelemetryAssembler& assembler,
                                           double seconds, std::int16_t x, std::int16_t r) {
  std::map<std::int64_t, Pose2> truth;
  mav::FrameDecoder decoder;
  std::vector<mav::Frame> frames;
  mav::Heartbeat hb;
  hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
  mav::ManualControl mc;
  mc.x = x;
  mc.r = r;
  const double dt = fw.simulator().config().dt_s;
  const int steps = static_cast<int>(std::lround(seconds / dt));
  for (int i = 0; i < steps; ++i) {
    const double t = fw.simulator().time_s();
    if (i % 50 == 0)
      fw.receive(frameOf(hb, 255, 190), t);
    if (i % 10 == 0)
      fw.receive(frameOf(mc, 255, 190), t);
    fw.advance(t + dt);
    truth[std::llround(fw.simulator().time_s() * 1000.0)] = fw.simulator().truePose();
    frames.clear();
    decoder.feed(fw.takeOutput(), frames);
    for (const auto& f : frames)
      assembler.onFrame(f, fw.simulator().time_s());
    assembler.tick(fw.simulator().time_s());
  }
  return truth;
}

// The Type (2,0) robot of paper 004 behind the firmware: its two floor sensors' counts reach the
// samples at the pose rate, and the host's optical-mouse odometry on them follows the robot's
// true motion (error-free sensors: quantisation only), as it does in-process.
TEST(TelemetryAssembler, TheFirmwaresFloorSensorCountsDriveTheHostsMouseOdometry) {
  const RobotProfile robot = testing::robotProfile("mouse_type20_004.json");
  SimConfig sim;
  sim.seed = 3;
  sim = idealSimConfig(sim);
  app::FirmwareCore fw(Simulator(testing::defaultMap(), robot, sim), {});
  ASSERT_EQ(fw.messagePeriod(mav::IrgsMouseCounts::kId).value_or(0.0), 0.05);
  EXPECT_EQ(fw.messagePeriod(mav::IrgsCasterEncoders::kId).value_or(1.0), 0.0);
  TelemetryAssembler assembler(robot);
  const auto truth = runWithTruth(fw, assembler, 6.0, 600, -250);  // an arc to the left
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 100u);
  std::size_t with_mouse = 0;
  for (const auto& s : samples)
    with_mouse += s.mouse.has_value() ? 1u : 0u;
  EXPECT_GE(with_mouse, samples.size() - 1);  // all but the very first sample
  EXPECT_GE(assembler.counters().mouse_frames, 110u);

  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kMouseOdometry;
  const Pose2 start = truth.begin()->second;
  EstimatorRunner runner(testing::defaultMap(), robot, start, config);
  double travelled = 0.0;
  for (const auto& s : samples) {
    const EstimatorStep& step = runner.feed(s);
    if (step.mouse_motion)
      travelled += step.mouse_motion->centre.norm();
  }
  EXPECT_GT(travelled, 1.0);
  EXPECT_EQ(runner.metrics().accepted, runner.metrics().readings);
  const auto it = truth.find(std::llround(samples.back().time_s * 1000.0));
  ASSERT_NE(it, truth.end());
  const Pose2 estimate = runner.lastStep().estimate;
  std::printf("mouse over the firmware's frames: %.3f m travelled, final error %.2f mm, %.3f deg\n",
              travelled, 1e3 * (estimate.position() - it->second.position()).norm(),
              radToDeg(std::abs(wrapAngle(estimate.theta - it->second.theta))));
  EXPECT_LT((estimate.position() - it->second.position()).norm(), 0.003)
      << estimate.x << " " << estimate.y << " vs " << it->second.x << " " << it->second.y;
  EXPECT_LT(std::abs(wrapAngle(estimate.theta - it->second.theta)), degToRad(0.2));
  EXPECT_GT(std::abs(wrapAngle(it->second.theta - start.theta)), 0.5);  // it really turned
}

// A floor gap beyond the sensors' lift-off height: the firmware reports them lifted, and the
// host's mouse odometry skips those intervals instead of taking the missing counts for rest.
TEST(TelemetryAssembler, LiftedFloorSensorsReachTheHostAsLifted) {
  const RobotProfile robot = testing::robotProfile("mouse_type20_004.json");
  SimConfig sim;
  sim = idealSimConfig(sim);
  sim.mouse_floor_gap_m = 0.005;  // the rig's max_lift_m is 2 mm
  app::FirmwareCore fw(Simulator(testing::defaultMap(), robot, sim), {});
  TelemetryAssembler assembler(robot);
  runWithTruth(fw, assembler, 2.0, 500, 0);
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 30u);
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kMouseOdometry;
  EstimatorRunner runner(testing::defaultMap(), robot, samples.front().odometry_pose, config);
  for (const auto& s : samples) {
    ASSERT_TRUE(s.mouse.has_value());
    EXPECT_EQ(s.mouse->right.status, MouseStatus::kLifted);
    EXPECT_EQ(s.mouse->left.status, MouseStatus::kLifted);
    runner.feed(s);
  }
  EXPECT_GT(runner.metrics().readings, 30);
  EXPECT_EQ(runner.metrics().accepted, 0);
  EXPECT_GT(
      (samples.back().odometry_pose.position() - samples.front().odometry_pose.position()).norm(),
      0.3);  // the wheels moved it
  EXPECT_LT(
      (runner.lastStep().estimate.position() - samples.front().odometry_pose.position()).norm(),
      1e-9);  // the mice saw nothing
}

// Paper 000's three-caster robot behind the firmware: the six encoders and the robot's own J+
// residual reach the samples (no IRGS_ENCODER_TICKS: it has no left/right wheels), and the
// host's three-caster EKF, fed only the 20 Hz samples, predicts with the robot's residual and
// its dead reckoning stays on the robot's own 1 ms J+ odometry.
TEST(TelemetryAssembler, TheFirmwaresCasterEncodersAndResidualReachTheHostsCasterEkf) {
  const RobotProfile robot = testing::robotProfile("caster3_000.json");
  SimConfig sim;
  sim.seed = 3;
  sim = typicalSimConfig(sim);  // the profile's caster errors: slip, backlash, radius spread
  app::FirmwareCore fw(Simulator(testing::defaultMap(), robot, sim), {});
  ASSERT_EQ(fw.messagePeriod(mav::IrgsCasterEncoders::kId).value_or(0.0), 0.05);
  EXPECT_EQ(fw.messagePeriod(mav::IrgsEncoderTicks::kId).value_or(1.0), 0.0);
  EXPECT_EQ(fw.messagePeriod(mav::IrgsMouseCounts::kId).value_or(1.0), 0.0);
  TelemetryAssembler assembler(robot);
  runWithTruth(fw, assembler, 6.0, 700, 200);  // an arc to the right
  const auto samples = assembler.takeReady();
  ASSERT_GE(samples.size(), 100u);
  ASSERT_TRUE(samples.back().casters.has_value());
  // The robot steps its casters in 1 ms periods: 6 s of them, each with its residual.
  EXPECT_NEAR(static_cast<double>(samples.back().casters->residual_periods), 6000.0, 60.0);
  EXPECT_GT(samples.back().casters->residual_sum_rad, 0.0);
  EXPECT_EQ(samples.back().left_ticks, 0);

  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kStereoEkfCaster;
  EstimatorRunner runner(testing::defaultMap(), robot, samples.front().odometry_pose, config);
  std::size_t from_robot = 0;
  for (const auto& s : samples) {
    const EstimatorStep& step = runner.feed(s);
    from_robot += step.caster_residual_from_robot ? 1u : 0u;
  }
  EXPECT_GE(from_robot, samples.size() - 2);
  const Pose2& robot_odometry = samples.back().odometry_pose;
  const Pose2& host = runner.lastStep().dead_reckoning;
  EXPECT_GT((robot_odometry.position() - samples.front().odometry_pose.position()).norm(), 1.0);
  std::printf(
      "caster over the firmware's frames: %zu samples, host J+ DR %.2f mm / %.3f deg off "
      "the robot's, mean residual used %.3e rad (robot's %.3e)\n",
      samples.size(), 1e3 * (host.position() - robot_odometry.position()).norm(),
      radToDeg(std::abs(wrapAngle(host.theta - robot_odometry.theta))),
      runner.metrics().mean_caster_residual_rad,
      samples.back().casters->residual_sum_rad /
          static_cast<double>(samples.back().casters->residual_periods));
  EXPECT_LT((host.position() - robot_odometry.position()).norm(), 0.005);
  EXPECT_LT(std::abs(wrapAngle(host.theta - robot_odometry.theta)), degToRad(0.2));
  // The robot's mean residual per period, not the one of the re-split 50 ms counts.
  const double robot_mean = samples.back().casters->residual_sum_rad /
                            static_cast<double>(samples.back().casters->residual_periods);
  EXPECT_NEAR(runner.metrics().mean_caster_residual_rad, robot_mean, 0.1 * robot_mean);
}

TEST(TelemetryAssembler, ARobotRestartStartsTheTimeBaseOver) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(lpn(60'000, 3.0f, 0.0f), 0.0);
  assembler.onFrame(att(60'000, 0.0f), 0.0);
  assembler.onFrame(lpn(20, 0.0f, 0.0f), 0.0);  // boot time far behind: rebooted
  assembler.onFrame(att(20, 0.0f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_DOUBLE_EQ(samples[1].time_s, 0.02);
  EXPECT_EQ(assembler.counters().restarts, 1u);
}

// Where in the byte stream the link noticed a reconnection must not change the samples: a replay
// of the same bytes (which may notice it elsewhere, or not at all) has to give the same poses.
TEST(TelemetryAssembler, AResetBetweenTwoPosesOfOneStepKeepsTheFirstLikeNoReset) {
  TelemetryAssembler with_reset(testing::thesisRobot());
  TelemetryAssembler without(testing::thesisRobot());
  for (TelemetryAssembler* a : {&with_reset, &without}) {
    a->onFrame(lpn(1000, 1.0f, 0.0f), 0.0);
    a->onFrame(att(1000, 0.0f), 0.0);
    if (a == &with_reset)
      a->reset();
    // The same step's pose again, differently rounded (as ODOMETRY repeats LPN + ATTITUDE).
    a->onFrame(lpn(1000, 1.0000001f, 0.0f), 0.0);
    a->onFrame(att(1000, 0.0f), 0.0);
    a->onFrame(lpn(1050, 1.1f, 0.0f), 0.0);
    a->onFrame(att(1050, 0.0f), 0.0);
    a->reset();  // the end: releases the complete 1050 step
  }
  const auto a = with_reset.takeReady();
  const auto b = without.takeReady();
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].time_s, b[i].time_s);
    EXPECT_EQ(a[i].odometry_pose.x, b[i].odometry_pose.x) << "sample " << i;
  }
  EXPECT_DOUBLE_EQ(a[0].odometry_pose.x, 1.0);
  EXPECT_EQ(with_reset.counters().restarts, 0u);
}

TEST(TelemetryAssembler, APoseOlderThanTheLastStepAfterAResetStartsANewTimeBase) {
  TelemetryAssembler assembler(testing::thesisRobot(), {.release_on_pose = true});
  assembler.onFrame(lpn(800, 1.0f, 0.0f), 0.0);  // less than kRestartJump_ms of robot time
  assembler.onFrame(att(800, 0.0f), 0.0);
  assembler.reset();                            // link back up: was it a reboot?
  assembler.onFrame(lpn(40, 0.0f, 0.0f), 0.0);  // yes: its clock is behind the last step
  assembler.onFrame(att(40, 0.0f), 0.0);
  const auto samples = assembler.takeReady();
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_DOUBLE_EQ(samples[1].time_s, 0.04);
  EXPECT_EQ(assembler.counters().restarts, 1u);
}

TEST(TelemetryAssembler, RejectsANonPositiveHoldTime) {
  EXPECT_THROW(TelemetryAssembler(testing::thesisRobot(), {.hold_s = 0.0}), std::invalid_argument);
  EXPECT_THROW(TelemetryAssembler(testing::thesisRobot(),
                                  {.hold_s = std::numeric_limits<double>::quiet_NaN()}),
               std::invalid_argument);
}

TEST(LinkedRobotCommands, ManualControlScalesClampsAndFlipsTheYawSign) {
  MotionLimits limits;
  limits.max_speed_mps = 0.4;
  limits.max_turn_rate_radps = 2.0;
  auto mc = manualControlFor({0.2, 0.5}, limits, 1);
  EXPECT_EQ(mc.target, 1);
  EXPECT_EQ(mc.x, 500);
  EXPECT_EQ(mc.r, -250);  // counter-clockwise is negative r
  mc = manualControlFor({-1.0, -9.0}, limits);
  EXPECT_EQ(mc.x, -1000);
  EXPECT_EQ(mc.r, 1000);
  EXPECT_THROW(manualControlFor({std::numeric_limits<double>::infinity(), 0.0}, limits),
               std::invalid_argument);
  limits.max_speed_mps = 0.0;
  EXPECT_THROW(manualControlFor({0.1, 0.0}, limits), std::invalid_argument);
}

TEST(LinkedRobotCommands, BehavioursMapToTheDialectCommands) {
  auto c = behaviourCommandLong(
      {.kind = RobotBehaviourKind::kMoveDistance, .distance_m = -0.5, .speed_mps = 0.2});
  EXPECT_EQ(c.command, 48100);
  EXPECT_FLOAT_EQ(c.param1, -0.5f);
  EXPECT_FLOAT_EQ(c.param2, 0.2f);
  c = behaviourCommandLong(
      {.kind = RobotBehaviourKind::kTurnAngle, .angle_rad = 1.0, .turn_rate_radps = 0.7});
  EXPECT_EQ(c.command, 48101);
  EXPECT_FLOAT_EQ(c.param1, 1.0f);
  EXPECT_FLOAT_EQ(c.param2, 0.7f);
  c = behaviourCommandLong({.kind = RobotBehaviourKind::kFollowWall,
                            .distance_m = 0.4,
                            .speed_mps = 0.1,
                            .wall_on_left = false,
                            .travel_m = 3.0});
  EXPECT_EQ(c.command, 48102);
  EXPECT_FLOAT_EQ(c.param1, 0.4f);
  EXPECT_FLOAT_EQ(c.param2, 1.0f);  // IRGS_WALL_SIDE_RIGHT
  EXPECT_FLOAT_EQ(c.param3, 0.1f);
  EXPECT_FLOAT_EQ(c.param4, 3.0f);
  EXPECT_EQ(behaviourCommandLong({.kind = RobotBehaviourKind::kStop}).command, 48103);
  c = behaviourCommandLong({.kind = RobotBehaviourKind::kEmergencyStop, .engage = false});
  EXPECT_EQ(c.command, 48104);
  EXPECT_FLOAT_EQ(c.param1, 0.0f);
  EXPECT_THROW(behaviourCommandLong({.kind = RobotBehaviourKind::kMoveDistance,
                                     .distance_m = std::numeric_limits<double>::quiet_NaN()}),
               std::invalid_argument);
  EXPECT_THROW(behaviourCommandLong({.kind = RobotBehaviourKind::kMoveDistance, .speed_mps = -0.1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
