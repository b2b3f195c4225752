#pragma once
// Goal travel and coverage as a host mission: the planned turning points (map frame = the
// robot's odometry frame, as the planner gave them) go to the robot as SEGMENTS primitives —
// the thesis's traveling algorithm runs on the robot (003_… section 4.3) — in chunks of at most
// motion::kMaxWaypoints; each turning point the robot reports reached counts, and the mission
// ends with the last one or when the robot stops short (a wall ahead, a bumper, no progress).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/mission/mission.hpp"

namespace irgs {

struct TravelMissionConfig {
  double speed_mps = 0.2;
  double turn_quantum_rad = degToRad(15.0);  // the thesis's quantised turns; 0: exact
  double stop_distance_m = 0.25;  // forward-sonar stop before the next turning point; 0: off
};

class TravelMission final : public Mission {
 public:
  // `points`: the path from the start, turning points only (the first is where the robot
  // stands). Throws std::invalid_argument for a non-finite point or config.
  TravelMission(std::vector<Vec2> points, TravelMissionConfig config = {});

  void onSample(const TelemetrySample& sample) override;
  void onReport(const motion::MotionReport& report) override;
  std::optional<MissionRequest> takeRequest() override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "travel"; }

  // Turning points reached so far (indices into the points), and the robot's odometry position
  // at each (where it believed it was).
  std::size_t reached() const { return reached_; }
  const std::vector<Vec2>& arrivalPositions() const { return arrivals_; }
  const std::vector<Vec2>& points() const { return points_; }

 private:
  void sendChunk();
  void finish(bool failed, std::string message);

  std::vector<Vec2> points_;
  TravelMissionConfig config_;
  std::size_t reached_ = 0;     // points_[0..reached_] reached (the start counts)
  std::size_t chunk_from_ = 0;  // first point of the chunk in flight is points_[chunk_from_ + 1]
  std::uint16_t next_id_ = 1;
  std::uint16_t active_id_ = 0;
  bool started_ = false;
  bool finished_ = false;
  bool failed_ = false;
  std::string message_;
  double total_m_ = 0.0;
  double done_m_ = 0.0;
  std::vector<Vec2> arrivals_;
  std::optional<MissionRequest> request_;
};

}  // namespace irgs
