#pragma once
// Path following of paper 004 (digest 5.6), after Canudas de Wit / Siciliano / Bastin (004's
// ref. [5]): the robot (a unicycle / Type (2,0) differential drive) reduces its signed distance l
// to a path and its heading error theta~ = theta - theta_r at the closest path point s:
//   (22) sdot       = v cos(theta~) / (1 - c(s) l)
//   (23) ldot       = v sin(theta~)
//   (24) theta~dot  = omega - v cos(theta~) c(s) / (1 - c(s) l)
//   (25) omega      = k(s, l, theta~, v)
// 004 does not give k; we use the Lyapunov law of the same textbook family (digest 5.6 [A]):
//   omega = v cos(theta~) c / (1 - c l) - k2 v l sin(theta~)/theta~ - k3 |v| theta~,
// with V = k2 l^2 / 2 + theta~^2 / 2, Vdot = -k3 |v| theta~^2 <= 0 (requires |c l| < 1).
//
// Conventions: l > 0 when the robot is LEFT of the path (of its tangent direction); c > 0 for a
// left (counter-clockwise) turn; metres, radians, seconds.

#include <vector>

#include "core/geometry/types.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

// A path of straight lines and circular arcs, continuous in position and tangent, so c(s) is
// exact and piecewise constant.
class ReferencePath {
 public:
  // Throws std::invalid_argument for a non-finite start.
  explicit ReferencePath(const Pose2& start);

  // Appends a straight piece. Throws std::invalid_argument unless length > 0 and finite.
  ReferencePath& addLine(double length_m);
  // Appends an arc turning by angle_rad (> 0 left, < 0 right) on a circle of radius_m. Throws
  // std::invalid_argument unless radius > 0, angle != 0 and both finite.
  ReferencePath& addArc(double radius_m, double angle_rad);

  struct Point {
    double s_m = 0.0;
    Pose2 pose;              // position and tangent heading theta_r
    double curvature = 0.0;  // c(s), 1/m
  };
  struct Projection {
    Point point;             // closest path point
    double lateral_m = 0.0;  // l, signed (left positive)
  };

  double length_m() const { return length_m_; }
  bool empty() const { return pieces_.empty(); }
  Pose2 start() const { return start_; }
  Pose2 end() const { return end_; }
  // The point at arc length s, clamped to [0, length].
  Point at(double s_m) const;
  // Closest point to p among the pieces overlapping [s_min, s_max] (arc length); the window keeps
  // the projection from jumping to another part of a path that comes back near itself.
  Projection project(const Vec2& p, double s_min_m, double s_max_m) const;
  // Samples every `step_m` (and the end), for drawing.
  std::vector<Point> sample(double step_m) const;

 private:
  struct Piece {
    Pose2 start;
    double s0_m = 0.0;
    double length_m = 0.0;
    double curvature = 0.0;  // 0 for a line
  };
  Point pointOn(const Piece& piece, double t_m) const;
  void append(double length_m, double curvature);

  Pose2 start_;
  Pose2 end_;
  double length_m_ = 0.0;
  std::vector<Piece> pieces_;
};

struct PathFollowerConfig {
  double speed_mps = 0.2;            // v, constant forward speed along the path [A]
  double k2 = 4.0;                   // 1/m^2, lateral gain [A]
  double k3 = 3.0;                   // 1/m, heading gain [A]
  double max_turn_rate_radps = 1.5;  // omega is clamped to this
  double min_denominator = 0.2;      // below this 1 - c l counts as singular
  double search_back_m = 0.2;        // projection window behind the last s
  double search_ahead_m = 1.0;       // and ahead of it
};

// Throws std::invalid_argument for non-finite or non-positive gains, speed, turn rate or window.
void validate(const PathFollowerConfig& config);

enum class PathFollowStatus {
  kFollowing,
  kReachedEnd,    // the closest point is the path's end and the robot is past it: stop
  kSingular,      // |1 - c l| too small (the robot is near an arc's centre): stop
  kInvalidInput,  // non-finite pose: stop
};
const char* toString(PathFollowStatus status);

struct PathFollowOutput {
  PathFollowStatus status = PathFollowStatus::kInvalidInput;
  VelocityCommand command;         // (v, omega); zero unless kFollowing
  double s_m = 0.0;                // closest path point
  double lateral_m = 0.0;          // l
  double heading_error_rad = 0.0;  // theta~ = theta - theta_r, wrapped
  double curvature = 0.0;          // c(s)
  double sdot_mps = 0.0;           // (22)
};

class PathFollower {
 public:
  // Throws std::invalid_argument for an empty path or an invalid config.
  PathFollower(ReferencePath path, PathFollowerConfig config = {});

  // One control period from the current pose estimate.
  PathFollowOutput update(const Pose2& pose);
  // Forgets the progress along the path (the next update searches from s = 0).
  void reset() { s_m_ = 0.0; }

  const ReferencePath& path() const { return path_; }
  const PathFollowerConfig& config() const { return config_; }
  double progress_m() const { return s_m_; }

 private:
  ReferencePath path_;
  PathFollowerConfig config_;
  double s_m_ = 0.0;
};

}  // namespace irgs
