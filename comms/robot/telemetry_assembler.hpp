#pragma once
// Assembles the robot's MAVLink telemetry into TelemetrySamples, pure: no Asio, no threads, no
// clock (the owner passes `now_s`, monotonic seconds). LinkedRobot runs it on the io thread.
//
// One sample per odometry time stamp. The pose comes from LOCAL_POSITION_NED + ATTITUDE,
// ODOMETRY or IRGS_POSE_2D (any of them; messages with the same time stamp are merged, the last
// one wins); MAVLink local NED/FRD is converted back to our frame exactly inverse to
// FirmwareCore (docs/protocol.md section 3): x = x_ned, y = -y_ned, theta = -yaw,
// omega = -yawspeed. DISTANCE_SENSOR (id = index into RobotProfile::sonars; current_distance
// > max_distance means no echo) and IRGS_SONAR_SCAN (sensors whose `fired` bit is set) add
// sonar readings; IRGS_ENCODER_TICKS and IRGS_CONTACT (bumper bits, IR proximity in mm,
// UINT16_MAX = nothing within the sensor's range) update the state every later sample carries.
//
// When is a sample complete? The firmware sends a time step's pose first and that step's sonar
// readings after it, so by default (release_on_pose = false) a sample is released when a message
// with a later time stamp arrives (the next step has begun) or, when nothing newer comes, hold_s
// after its pose was complete. Sonar readings therefore always ride on the pose of their own time
// stamp, at the cost of up to one telemetry period of latency. With release_on_pose = true a
// sample leaves as soon as its pose is complete (lowest latency); readings stamped with its time
// that arrive afterwards ride on the next sample (their pose then lags by one period).
// Readings older than the sample being assembled join it (IRGS_SONAR_SCAN carries the time of
// its newest reading, which may precede the pose). When the hold timer released a sample and
// readings of its time stamp (or older) still arrive before any newer step, they leave in a
// supplementary sample with the same time and pose: so which pose a reading rides on depends
// on the byte stream alone, never on the timer, and a replay of the recorded bytes builds the
// same map as the live session did.
//
// IRGS_MOUSE_COUNTS (two floor sensors, cumulative counts; the state is the worst of the
// readings since the previous frame, an unknown one taken as lifted) and IRGS_CASTER_ENCODERS
// (six cumulative counts and, when flagged valid, the robot's own J+ residual sum and period
// count) become TelemetrySample::mouse and ::casters, carried like the encoder ticks: every
// sample from the first such frame on has the newest.
//
// SCALED_IMU (body FRD, mrad/s; docs/protocol.md) gives the gyro: rate = -zgyro (our z is up),
// temperature from its cdegC extension (0 = not provided: 25 C, GyroReading's default), and
// saturated when zgyro sits at the int16 limit. The rate is the gyro's raw indicated rate; the
// profile's gyro calibration is applied by the estimator, as for the simulator's gyro.
//
// A time stamp more than kRestartJump_ms older than the newest one means the robot restarted:
// the assembler starts over (counted in restarts). Call reset() when the link is re-established.

#include <cstdint>
#include <optional>
#include <vector>

#include "comms/mavlink/frame.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::comms {

struct TelemetryAssemblerConfig {
  bool release_on_pose = false;  // see above
  double hold_s = 0.1;           // release a complete sample after this long without newer data
  // Sonar readings kept while no pose has arrived yet; older ones are dropped (and counted).
  std::size_t max_unposed_readings = 1024;
  // SCALED_IMU's yaw rate becomes TelemetrySample::gyro (zero-order hold: every sample carries
  // the newest reading) while the reading is at most this much older than the sample, robot
  // time; older readings are not used (an IMU stream that stopped is not a gyro at rest).
  double max_gyro_age_s = 0.3;
};

struct TelemetryAssemblerCounters {
  std::uint64_t samples = 0;             // released
  std::uint64_t sonar_readings = 0;      // taken into samples
  std::uint64_t ignored_readings = 0;    // unknown sensor index, zero range, dropped without pose
  std::uint64_t stale_poses = 0;         // pose messages older than the sample being assembled
  std::uint64_t duplicate_poses = 0;     // further pose messages of a step that had its pose
  std::uint64_t late_samples = 0;        // supplementary samples of readings after a hold release
  std::uint64_t unsupported_frames = 0;  // ODOMETRY in a frame we cannot convert
  std::uint64_t restarts = 0;            // robot clock jumped back (reboot)
  std::uint64_t gyro_readings = 0;       // SCALED_IMU frames taken as gyro readings
  std::uint64_t mouse_frames = 0;        // IRGS_MOUSE_COUNTS frames taken
  std::uint64_t caster_frames = 0;       // IRGS_CASTER_ENCODERS frames taken
};

class TelemetryAssembler {
 public:
  static constexpr std::int64_t kRestartJump_ms = 1000;

  // Throws std::invalid_argument when hold_s is not finite and > 0.
  explicit TelemetryAssembler(RobotProfile profile, TelemetryAssemblerConfig config = {});

  // Takes one frame from the robot (frames that carry no telemetry are ignored).
  void onFrame(const mavlink::Frame& frame, double now_s);
  // Releases a complete sample that waited hold_s (call every few tens of milliseconds).
  void tick(double now_s);
  // Link re-established: releases the sample being assembled (when complete) and lets the
  // first pose after it decide whether the robot restarted. A pose older than the last released
  // step starts a new time base; otherwise the robot's clock goes on, and a pose of a step
  // already released stays stale as if the link had never dropped, so the samples depend on the
  // byte stream alone, not on where in it the reconnection was noticed (a replay of the same
  // bytes gives the same samples). The state carried from sample to sample (ticks, bumpers) is
  // kept.
  void reset();

  // Released samples, oldest first.
  std::vector<TelemetrySample> takeReady();
  bool hasReady() const { return !ready_.empty(); }

  const TelemetryAssemblerCounters& counters() const { return counters_; }
  const TelemetryAssemblerConfig& config() const { return config_; }

 private:
  struct Assembly {
    std::optional<std::int64_t> time_ms;  // robot boot time of the sample
    TelemetrySample sample;
    bool has_xy = false;
    bool has_theta = false;
    bool has_velocity = false;  // body v from ODOMETRY / IRGS_POSE_2D
    bool has_omega = false;
    double ned_vx = 0.0;  // LOCAL_POSITION_NED velocity, converted once theta is known
    double ned_vy = 0.0;
    bool has_ned_velocity = false;
    std::optional<double> complete_since_s;  // when the pose became complete
  };

  // Moves the assembly to `time_ms` (releasing the current sample when it has a pose and the
  // time is newer). Returns false when the message is stale and must be ignored (poses only).
  bool advanceTo(std::int64_t time_ms, bool is_pose);
  // True (and counted) when this step already has a complete pose: later pose messages of
  // the same step are ignored.
  bool poseAlreadyComplete();
  void poseUpdated(double now_s);
  void release();
  void addReading(const SonarReading& reading);
  // Readings stamped with the time of a sample the hold timer released (or older) while no
  // newer step has begun: they ride on that sample's pose in a supplementary sample
  // (`late_`), as they would have had the timer waited. Default mode only.
  bool belongsToHeldRelease(std::int64_t time_ms) const;
  void addLateReading(const SonarReading& reading);
  void flushLate();
  void onLocalPosition(const mavlink::Frame& frame, double now_s);

  RobotProfile profile_;
  TelemetryAssemblerConfig config_;
  Assembly current_;
  std::optional<std::int64_t> newest_ms_;    // newest time stamp of the current time base
  std::optional<std::int64_t> released_ms_;  // time of the last released sample
  std::optional<Pose2> last_pose_;           // pose of the last released sample
  VelocityCommand last_velocity_{};          // velocity of the last released sample
  bool released_by_hold_ = false;            // the last release was the hold timer's
  bool clock_in_doubt_ = false;              // reset(): the next pose tells if it restarted
  std::optional<TelemetrySample> late_;      // supplementary sample for late readings
  TelemetrySample carried_;  // ticks, floor sensors, casters, bumpers, proximity: the newest
  std::optional<GyroReading> gyro_;  // the newest SCALED_IMU yaw rate
  std::int64_t gyro_ms_ = 0;         // its robot time
  void attachGyro(TelemetrySample& sample) const;
  std::vector<TelemetrySample> ready_;
  TelemetryAssemblerCounters counters_;
};

}  // namespace irgs::comms
