// The re-run engine (app/recording/rerun_engine.hpp) on a robot byte stream built here: the
// thesis robot's firmware messages (heartbeat, IRGS_POSE_2D, IRGS_ENCODER_TICKS, IRGS_SONAR_SCAN)
// for a straight drive past walls, encoded as the robot encodes them and stored as a recording's
// received rows, with simulator truth a known offset away.

#include "app/recording/rerun_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/recording/rerun_output.hpp"
#include "app/recording/rerun_parameters.hpp"
#include "comms/link/frame_tap.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "core/robot/robot_profile_file.hpp"

namespace irgs::recording {
namespace {

namespace mav = comms::mavlink;

constexpr int kPoses = 100;  // 5 s at 20 Hz
constexpr double kSpeed_mps = 0.2;
constexpr double kTruthOffset_m = 0.05;  // truth is this far to the left of the odometry

RobotProfile thesisRobot() {
  RobotProfileResult r =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!r.profile)
    throw std::runtime_error("thesis robot profile unreadable");
  return *r.profile;
}

void addReceived(Recording& rec, double t, const mav::EncodedFrame& frame) {
  RecordedFrame& f = rec.frames.emplace_back();
  f.t_s = t;
  f.dir = static_cast<std::uint8_t>(comms::TapDirection::kReceived);
  f.bytes.assign(frame.view().begin(), frame.view().end());
}

// A robot driving along +x at y = 0 between walls 0.8 m to its sides: every sonar fires each
// step with a range that depends on the step (so the map has structure).
Recording drivePastWalls(const RobotProfile& profile) {
  Recording rec;
  rec.meta["format_version"] = "1";
  rec.meta["robot"] = profile.name;
  mav::FrameEncoder encoder(1, 1);
  // A ground station's own heartbeat echoed on the link: ignored, as LinkedRobot ignores it.
  {
    mav::FrameEncoder gcs(255, 190);
    mav::Heartbeat hb;
    hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
    addReceived(rec, 0.0, gcs.encode(hb));
  }
  const double metres_per_tick = profile.drive.metresPerTick();
  for (int i = 0; i < kPoses; ++i) {
    const double t = 0.5 + 0.05 * i;
    const double x = kSpeed_mps * 0.05 * i;
    if (i % 20 == 0) {
      mav::Heartbeat hb;
      hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
      addReceived(rec, t, encoder.encode(hb));
    }
    const auto boot_ms = static_cast<std::uint32_t>(2000 + 50 * i);
    mav::IrgsPose2d pose;
    pose.time_boot_ms = boot_ms;
    pose.x = static_cast<float>(x);
    pose.v = static_cast<float>(kSpeed_mps);
    addReceived(rec, t, encoder.encode(pose));
    mav::IrgsEncoderTicks ticks;
    ticks.time_usec = std::uint64_t{boot_ms} * 1000;
    ticks.left_ticks = ticks.right_ticks = std::llround(x / metres_per_tick);
    addReceived(rec, t + 0.001, encoder.encode(ticks));
    mav::IrgsSonarScan scan;
    scan.time_boot_ms = boot_ms;
    scan.count = static_cast<std::uint8_t>(profile.sonars.size());
    scan.fired = static_cast<std::uint16_t>((1u << profile.sonars.size()) - 1);
    for (std::size_t s = 0; s < profile.sonars.size(); ++s)
      scan.range[s] = static_cast<std::uint16_t>(600 + 10 * ((i + static_cast<int>(s)) % 40));
    addReceived(rec, t + 0.002, encoder.encode(scan));
    rec.truth.push_back({t, x, kTruthOffset_m, 0.0});
  }
  return rec;
}

class RerunEngine : public ::testing::Test {
 protected:
  RobotProfile profile_ = thesisRobot();
  Recording recording_ = drivePastWalls(profile_);
  WorldMap map_;
};

TEST_F(RerunEngine, DecodesEverySampleAndReadingThroughTheLivePath) {
  const DecodedRecording decoded = decodeRecording(recording_, profile_);
  ASSERT_EQ(decoded.samples.size(), static_cast<std::size_t>(kPoses));
  EXPECT_EQ(decoded.stats.link_ups, 1u);
  EXPECT_EQ(decoded.stats.decoder.bad_crc, 0u);
  EXPECT_EQ(decoded.stats.assembler.sonar_readings, kPoses * profile_.sonars.size());
  for (int i = 0; i < kPoses; ++i) {
    const DecodedSample& s = decoded.samples[static_cast<std::size_t>(i)];
    EXPECT_NEAR(s.sample.time_s, 2.0 + 0.05 * i, 1e-9);
    EXPECT_NEAR(s.sample.odometry_pose.x, kSpeed_mps * 0.05 * i, 1e-6);
    EXPECT_EQ(s.sample.sonar.size(), profile_.sonars.size());
    // On the recording's clock, one offset for the whole robot clock: the least delayed sample
    // is the last one, released when its last chunk (the scan, 2 ms after the pose) arrived.
    EXPECT_NEAR(s.recording_t_s, 0.5 + 0.05 * i + 0.002, 1e-9);
  }
}

TEST_F(RerunEngine, TheRecordedParametersReproduceTheRecordedRunExactly) {
  const RerunParameters recorded;
  const RerunResult r = rerunRecording(recording_, profile_, map_, recorded, recorded);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.samples, static_cast<std::size_t>(kPoses));
  EXPECT_GT(r.recorded.grid.observedCellCount(), 10000u);
  EXPECT_TRUE(r.metrics.grid.identical);
  EXPECT_EQ(r.metrics.grid.agreement, 1.0);
  EXPECT_EQ(r.metrics.grid.occupied.f1, 1.0);
  EXPECT_GT(r.metrics.grid.reference_occupied, 100u);
  EXPECT_EQ(r.metrics.pose.compared, static_cast<std::size_t>(kPoses));
  EXPECT_EQ(r.metrics.pose.max_position_m, 0.0);
  // Against the truth, odometry is off by exactly the injected offset.
  ASSERT_TRUE(r.recorded.truth_error);
  // (IRGS_POSE_2D carries floats: 1e-5 m.)
  EXPECT_NEAR(r.recorded.truth_error->rms_position_m, kTruthOffset_m, 1e-5);
  EXPECT_NEAR(r.recorded.truth_error->max_position_m, kTruthOffset_m, 1e-5);
}

TEST_F(RerunEngine, AShorterValidDistanceRemovesTheEchoesFromTheMap) {
  const RerunParameters recorded;
  RerunParameters changed;
  ASSERT_EQ(setRerunParameter(changed, "sonar_valid_distance_m", "0.5"), std::nullopt);
  const RerunResult r = rerunRecording(recording_, profile_, map_, recorded, changed);
  ASSERT_EQ(r.error, "");
  EXPECT_FALSE(r.metrics.grid.identical);
  EXPECT_EQ(r.metrics.grid.candidate_occupied, 0u);  // every echo is beyond 0.5 m
  EXPECT_EQ(r.metrics.grid.occupied.f1, 0.0);
  EXPECT_LT(r.metrics.grid.agreement, 0.9);
  EXPECT_EQ(r.metrics.pose.max_position_m, 0.0);  // the mapper does not move the robot
}

TEST_F(RerunEngine, ACoarserGridIsComparedOnItsOwnCells) {
  const RerunParameters recorded;
  RerunParameters changed;
  ASSERT_EQ(setRerunParameter(changed, "grid_resolution_m", "0.05"), std::nullopt);
  const RerunResult r = rerunRecording(recording_, profile_, map_, recorded, changed);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.metrics.grid.resolution_m, 0.05);
  EXPECT_FALSE(r.metrics.grid.identical);
  // The same readings: most coarse cells agree, the occupied arcs lie within a cell or two.
  EXPECT_GT(r.metrics.grid.agreement, 0.7);
  EXPECT_LT(r.metrics.grid.agreement, 1.0);
  EXPECT_GT(r.metrics.grid.occupied_tolerant.f1, 0.8);
}

TEST_F(RerunEngine, DeadReckoningFromTheTicksFollowsTheOdometry) {
  const RerunParameters recorded;
  RerunParameters changed;
  ASSERT_EQ(setRerunParameter(changed, "estimator", "dr"), std::nullopt);
  ASSERT_EQ(setRerunParameter(changed, "map_on_estimate", "1"), std::nullopt);
  const RerunResult r = rerunRecording(recording_, profile_, map_, recorded, changed);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.rerun.trajectory.size(), static_cast<std::size_t>(kPoses));
  // Straight-line ticks rounded to whole counts: the estimate stays within a tick of odometry.
  EXPECT_LT(r.metrics.pose.max_position_m, 2.0 * profile_.drive.metresPerTick());
  EXPECT_GT(r.rerun.trajectory.back().pose.x, 0.9);
  EXPECT_GT(r.metrics.grid.occupied_tolerant.f1, 0.9);
}

TEST_F(RerunEngine, ACancelledRunReportsItAndABadParameterIsAnError) {
  const RerunParameters recorded;
  RerunResult cancelled = rerunRecording(recording_, profile_, map_, recorded, recorded,
                                         [](double f) { return f < 0.5; });
  EXPECT_TRUE(cancelled.cancelled);
  RerunParameters bad;
  bad.grid_resolution_m = -1.0;  // bypassing the setter's range check
  const RerunResult r = rerunRecording(recording_, profile_, map_, recorded, bad);
  EXPECT_FALSE(r.error.empty());
  Recording empty;
  EXPECT_NE(rerunRecording(empty, profile_, map_, recorded, recorded).error.find("no received"),
            std::string::npos);
}

TEST_F(RerunEngine, WritesMapsTrajectoriesAndMetrics) {
  RerunParameters changed;
  ASSERT_EQ(setRerunParameter(changed, "occupied_log_odds", "0.3"), std::nullopt);
  const RerunResult r = rerunRecording(recording_, profile_, map_, RerunParameters{}, changed);
  ASSERT_EQ(r.error, "");
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("irgs-rerun-out-" + std::to_string(::getpid()));
  ASSERT_EQ(writeRerunOutputs(r, dir, "synthetic.irgsrec"), "");
  for (const char* name : {"recorded_map.png", "recorded_map.yaml", "recorded_map.pgm",
                           "rerun_map.png", "rerun_map.yaml", "recorded_grid.csv", "rerun_grid.csv",
                           "recorded_trajectory.csv", "rerun_trajectory.csv", "metrics.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  std::ifstream in(dir / "metrics.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["changed_parameters"], nlohmann::json::array({"occupied_log_odds"}));
  EXPECT_EQ(j["samples"], kPoses);
  EXPECT_EQ(j["rerun"]["parameters"]["occupied_log_odds"], "0.3");
  EXPECT_LT(j["grid"]["agreement"].get<double>(), 1.0);
  EXPECT_NEAR(j["recorded"]["truth_error"]["rms_position_m"].get<double>(), kTruthOffset_m, 1e-5);
  std::filesystem::remove_all(dir);
}

TEST(RerunParameters, ParseCheckAndComeFromTheRecordingsMeta) {
  RerunParameters p;
  EXPECT_EQ(rerunParameterValue(p, "grid_resolution_m"), "0.01");
  EXPECT_EQ(rerunParameterValue(p, "estimator"), "none");
  EXPECT_EQ(rerunParameterValue(p, "gate"), "inf");
  EXPECT_TRUE(setRerunParameter(p, "nope", "1"));
  EXPECT_TRUE(setRerunParameter(p, "grid_resolution_m", "abc"));
  EXPECT_TRUE(setRerunParameter(p, "grid_resolution_m", "0"));  // below the range
  EXPECT_TRUE(setRerunParameter(p, "estimator", "kalman"));
  EXPECT_TRUE(setRerunParameterAssignment(p, "grid_resolution_m"));
  EXPECT_EQ(p.grid_resolution_m, 0.01);  // unchanged by the refusals
  EXPECT_EQ(setRerunParameterAssignment(p, "eps2_deg=20"), std::nullopt);
  EXPECT_NEAR(p.estimator_config.ekf.eps2_rad, degToRad(20.0), 1e-12);
  EXPECT_EQ(changedRerunParameters(RerunParameters{}, p), std::vector<std::string>{"eps2_deg"});

  std::vector<std::string> warnings;
  const RerunParameters recorded = recordedRerunParameters({{"robot", "thesis_robot"},
                                                            {"param.grid_resolution_m", "0.02"},
                                                            {"param.sonar_valid_distance_m", "2.5"},
                                                            {"param.bogus", "1"}},
                                                           &warnings);
  EXPECT_EQ(recorded.grid_resolution_m, 0.02);
  EXPECT_EQ(recorded.validDistance(), 2.5);
  EXPECT_EQ(warnings.size(), 1u);
}

}  // namespace
}  // namespace irgs::recording
