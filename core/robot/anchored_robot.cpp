#include "core/robot/anchored_robot.hpp"

#include <type_traits>
#include <utility>

namespace irgs {
namespace {

Vec2 mapped(const Pose2& to_from, const Vec2& p) {
  return to_from.toWorld(p);
}

}  // namespace

motion::Primitive transformed(const motion::Primitive& primitive, const Pose2& to_from) {
  motion::Primitive out = primitive;
  std::visit(
      [&](auto& spec) {
        using S = std::decay_t<decltype(spec)>;
        if constexpr (std::is_same_v<S, motion::TurnSpec>) {
          if (spec.absolute)
            spec.angle_rad = wrapAngle(spec.angle_rad + to_from.theta);
        } else if constexpr (std::is_same_v<S, motion::SegmentsSpec> ||
                             std::is_same_v<S, motion::FollowPathSpec>) {
          for (std::size_t i = 0; i < spec.count; ++i)
            spec.points[i] = mapped(to_from, spec.points[i]);
        }
      },
      out.spec);
  return out;
}

AnchoredRobot::AnchoredRobot(Robot& robot, std::optional<Pose2> anchor)
    : robot_(robot), anchor_(anchor) {}

std::vector<TelemetrySample> AnchoredRobot::toMap(std::vector<TelemetrySample> samples) {
  if (!anchor_)
    return samples;
  if (!first_odometry_ && !samples.empty()) {
    first_odometry_ = samples.front().odometry_pose;
    map_from_odometry_ = anchor_->compose(first_odometry_->inverse());
  }
  for (TelemetrySample& s : samples) {
    s.odometry_pose = map_from_odometry_.compose(s.odometry_pose);
    if (s.true_pose)
      s.true_pose = map_from_odometry_.compose(*s.true_pose);
  }
  return samples;
}

std::vector<TelemetrySample> AnchoredRobot::update(double wall_elapsed_s) {
  return toMap(robot_.update(wall_elapsed_s));
}

std::vector<TelemetrySample> AnchoredRobot::finish() {
  return toMap(robot_.finish());
}

MotionControl* AnchoredRobot::motionControl() {
  return robot_.motionControl() ? this : nullptr;
}

bool AnchoredRobot::supports(motion::PrimitiveKind kind) const {
  const MotionControl* inner = const_cast<Robot&>(robot_).motionControl();
  return inner && inner->supports(kind);
}

void AnchoredRobot::start(const motion::Primitive& primitive) {
  if (MotionControl* inner = robot_.motionControl())
    inner->start(transformed(primitive, map_from_odometry_.inverse()));
}

void AnchoredRobot::cancel() {
  if (MotionControl* inner = robot_.motionControl())
    inner->cancel();
}

std::vector<motion::MotionReport> AnchoredRobot::takeReports() {
  MotionControl* inner = robot_.motionControl();
  if (!inner)
    return {};
  std::vector<motion::MotionReport> reports = inner->takeReports();
  for (motion::MotionReport& r : reports)
    r.pose = map_from_odometry_.compose(r.pose);
  return reports;
}

}  // namespace irgs
