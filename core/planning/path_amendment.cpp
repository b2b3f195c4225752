#include "core/planning/path_amendment.hpp"

#include <cmath>
#include <stdexcept>

#include "core/planning/free_space.hpp"

namespace irgs {
namespace {

void requireValid(const TravelTimeModel& m) {
  if (!std::isfinite(m.speed_mps) || m.speed_mps <= 0.0 || !std::isfinite(m.turn_rate_radps) ||
      m.turn_rate_radps <= 0.0 || !std::isfinite(m.turn_stop_s) || m.turn_stop_s < 0.0)
    throw std::invalid_argument("TravelTimeModel: speed and turn rate > 0, stop time >= 0");
}

// Direction change at interior vertex i of pts.
bool isTurn(const std::vector<Vec2>& pts, std::size_t i) {
  if (i == 0 || i + 1 >= pts.size())
    return false;
  const Vec2 d1 = pts[i] - pts[i - 1], d2 = pts[i + 1] - pts[i];
  const double angle = std::atan2(cross(d1, d2), d1.dot(d2));
  return std::abs(angle) > kStraightTolerance_rad;
}

}  // namespace

std::vector<Vec2> compressPath(const std::vector<Vec2>& points) {
  std::vector<Vec2> dedup;
  for (const Vec2& p : points)
    if (dedup.empty() || (p - dedup.back()).norm() > 1e-12)
      dedup.push_back(p);
  if (dedup.size() < 3)
    return dedup;
  std::vector<Vec2> out{dedup.front()};
  for (std::size_t i = 1; i + 1 < dedup.size(); ++i) {
    const Vec2 d1 = dedup[i] - out.back(), d2 = dedup[i + 1] - dedup[i];
    if (std::abs(std::atan2(cross(d1, d2), d1.dot(d2))) > kStraightTolerance_rad)
      out.push_back(dedup[i]);
  }
  out.push_back(dedup.back());
  return out;
}

int countTurns(const std::vector<Vec2>& points) {
  const std::vector<Vec2> c = compressPath(points);
  return c.size() < 3 ? 0 : static_cast<int>(c.size()) - 2;
}

double pathLength(const std::vector<Vec2>& points) {
  double l = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i)
    l += (points[i] - points[i - 1]).norm();
  return l;
}

double travelTime(const std::vector<Vec2>& points, const TravelTimeModel& model,
                  std::optional<double> initial_heading_rad) {
  requireValid(model);
  const std::vector<Vec2> c = compressPath(points);
  double t = pathLength(c) / model.speed_mps;
  std::optional<double> heading = initial_heading_rad;
  for (std::size_t i = 1; i < c.size(); ++i) {
    const Vec2 d = c[i] - c[i - 1];
    const double h = std::atan2(d.y(), d.x());
    if (heading) {
      const double turn = std::abs(wrapAngle(h - *heading));
      if (turn > kStraightTolerance_rad)
        t += model.turn_stop_s + turn / model.turn_rate_radps;
    }
    heading = h;
  }
  return t;
}

bool headingOnQuantum(double heading_rad, double quantum_rad, double tolerance_rad) {
  if (quantum_rad <= 0.0)
    return true;
  const double r = heading_rad / quantum_rad;
  return std::abs(r - std::round(r)) * quantum_rad <= tolerance_rad;
}

AmendResult amendPath(const PlanningGrid& grid, const std::vector<Vec2>& path,
                      const std::vector<std::size_t>& wave_indices, const AmendOptions& options) {
  requireValid(options.time_model);
  if (options.search_depth < 1)
    throw std::invalid_argument("amendPath: search_depth must be >= 1");
  if (!std::isfinite(options.turn_quantum_rad) || options.turn_quantum_rad < 0.0 ||
      !std::isfinite(options.heading_tolerance_rad) || options.heading_tolerance_rad < 0.0)
    throw std::invalid_argument("amendPath: quantum and tolerance must be finite and >= 0");
  std::vector<bool> wave_at(path.size(), false);
  for (const std::size_t w : wave_indices) {
    if (w >= path.size())
      throw std::invalid_argument("amendPath: wave point index out of range");
    wave_at[w] = true;
  }
  const TravelTimeModel& tm = options.time_model;
  AmendResult result;
  // Working polyline: the path's turning points, its ends and its wave points.
  std::vector<Vec2> pts;
  std::vector<bool> wave;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!pts.empty() && (path[i] - pts.back()).norm() <= 1e-12) {
      wave.back() = wave.back() || wave_at[i];
      continue;
    }
    const bool keep = i == 0 || i + 1 == path.size() || wave_at[i] || isTurn(path, i);
    if (keep) {
      pts.push_back(path[i]);
      wave.push_back(wave_at[i]);
    }
  }
  result.points = compressPath(pts);
  result.turns_before = countTurns(result.points);
  result.length_before_m = pathLength(result.points);
  result.time_before_s = travelTime(result.points, tm);
  result.turns_after = result.turns_before;
  result.length_after_m = result.length_before_m;
  result.time_after_s = result.time_before_s;
  if (pts.size() < 3 || !polylineIsFree(grid, pts))
    return result;

  double time_now = travelTime(pts, tm);
  const auto splice = [&](std::size_t i1, std::size_t i2, const std::vector<Vec2>& middle) {
    std::vector<Vec2> out(pts.begin(), pts.begin() + static_cast<std::ptrdiff_t>(i1) + 1);
    out.insert(out.end(), middle.begin(), middle.end());
    out.insert(out.end(), pts.begin() + static_cast<std::ptrdiff_t>(i2), pts.end());
    return out;
  };
  for (std::size_t k = 1; k + 1 < pts.size(); ++k) {
    if (!wave[k])
      continue;
    // P1 candidates: the last turning point before the wave point (003's P1), then up to
    // search_depth - 1 earlier ones (or the start); P2 likewise after it.
    std::vector<std::size_t> firsts, seconds;
    for (std::size_t i = k; i-- > 0 && firsts.size() < options.search_depth;)
      if (i == 0 || isTurn(pts, i))
        firsts.push_back(i);
    for (std::size_t j = k + 1; j < pts.size() && seconds.size() < options.search_depth; ++j)
      if (j + 1 == pts.size() || isTurn(pts, j))
        seconds.push_back(j);
    std::vector<Vec2> best;
    double best_time = time_now - 1e-9;
    std::size_t i1 = 0, i2 = 0;
    for (const std::size_t c1 : firsts)
      for (const std::size_t c2 : seconds) {
        const Vec2 p1 = pts[c1], p2 = pts[c2];
        // (003 Fig. 4.7) rectangle with diagonal P1-P2, split into two triangles.
        const Vec2 corners[2] = {Vec2(p2.x(), p1.y()), Vec2(p1.x(), p2.y())};
        const bool free_tri[2] = {triangleIsFree(grid, p1, corners[0], p2),
                                  triangleIsFree(grid, p1, corners[1], p2)};
        std::vector<std::vector<Vec2>> candidates;
        const Vec2 d = p2 - p1;
        const bool straight_ok = headingOnQuantum(
            std::atan2(d.y(), d.x()), options.turn_quantum_rad, options.heading_tolerance_rad);
        if (options.mode == AmendMode::kStraightFirst && straight_ok &&
            (free_tri[0] || free_tri[1]))
          candidates.push_back({});
        else
          for (int t = 0; t < 2; ++t)
            if (free_tri[t])
              candidates.push_back({corners[t]});
        for (const auto& middle : candidates) {
          std::vector<Vec2> trial = splice(c1, c2, middle);
          const double t = travelTime(trial, tm);
          if (t < best_time && polylineIsFree(grid, trial)) {
            best_time = t;
            best = std::move(trial);
            i1 = c1;
            i2 = c2;
          }
        }
      }
    if (best.empty())
      continue;
    // Rebuild the wave flags: the replaced run held this and possibly later wave points.
    std::vector<bool> new_wave(wave.begin(), wave.begin() + static_cast<std::ptrdiff_t>(i1) + 1);
    new_wave.resize(best.size() - (pts.size() - i2), false);
    new_wave.insert(new_wave.end(), wave.begin() + static_cast<std::ptrdiff_t>(i2), wave.end());
    pts = std::move(best);
    wave = std::move(new_wave);
    time_now = best_time;
    ++result.wave_points_amended;
    k = i1;  // continue after P1 (the loop's ++k)
  }
  pts = compressPath(pts);
  if (options.line_of_sight && pts.size() > 2) {
    std::vector<Vec2> out{pts.front()};
    std::size_t i = 0;
    while (i + 1 < pts.size()) {
      std::size_t j = pts.size() - 1;
      for (; j > i + 1; --j) {
        const Vec2 dj = pts[j] - pts[i];
        if (headingOnQuantum(std::atan2(dj.y(), dj.x()), options.turn_quantum_rad,
                             options.heading_tolerance_rad) &&
            segmentIsFree(grid, pts[i], pts[j]))
          break;
      }
      out.push_back(pts[j]);
      i = j;
    }
    out = compressPath(out);
    if (travelTime(out, tm) <= time_now)
      pts = std::move(out);
  }
  result.points = pts;
  result.turns_after = countTurns(pts);
  result.length_after_m = pathLength(pts);
  result.time_after_s = travelTime(pts, tm);
  return result;
}

}  // namespace irgs
