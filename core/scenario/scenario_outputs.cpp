#include "core/scenario/scenario_outputs.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <system_error>

#include "core/io/atomic_file.hpp"
#include "core/io/png_writer.hpp"
#include "core/world/ros_map.hpp"

namespace irgs {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

// Fixed-precision number formatting: stable text for byte-identical reruns.
std::string fixed(double value, int decimals) {
  std::array<char, 64> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.*f", decimals, value);
  return buffer.data();
}

double rounded(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(value * scale) / scale;
}

nlohmann::json poseJson(const Pose2& pose) {
  return {{"x_m", rounded(pose.x, 6)},
          {"y_m", rounded(pose.y, 6)},
          {"theta_rad", rounded(pose.theta, 6)},
          {"theta_deg", rounded(radToDeg(pose.theta), 4)}};
}

class Picture {
 public:
  Picture(int width, int height) : width_(width), height_(height) {
    pixels_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 0);
  }
  void set(int x, int y, const Rgb& c) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_)
      return;
    const auto i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                    static_cast<std::size_t>(x)) *
                   3;
    pixels_[i] = c[0];
    pixels_[i + 1] = c[1];
    pixels_[i + 2] = c[2];
  }
  // Bresenham line, `thickness` pixels wide (square brush).
  void line(int x0, int y0, int x1, int y1, const Rgb& c, int thickness) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    const int r = thickness / 2;
    while (true) {
      for (int oy = -r; oy <= r; ++oy) {
        for (int ox = -r; ox <= r; ++ox)
          set(x0 + ox, y0 + oy, c);
      }
      if (x0 == x1 && y0 == y1)
        break;
      const int e2 = 2 * err;
      if (e2 >= dy) {
        err += dy;
        x0 += sx;
      }
      if (e2 <= dx) {
        err += dx;
        y0 += sy;
      }
    }
  }
  std::string png() const { return encodePng(width_, height_, 3, pixels_); }

 private:
  int width_;
  int height_;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace

std::string metricsJson(const ScenarioMetrics& m, const ScenarioRunInfo& info) {
  nlohmann::ordered_json doc;
  doc["map"] = info.map_source;
  doc["robot"] = info.robot_name;
  doc["seed"] = info.seed;
  doc["duration_s"] = rounded(m.duration_s, 6);
  doc["steps"] = m.steps;
  doc["distance_travelled_m"] = rounded(m.distance_travelled_m, 6);
  doc["rotation_travelled_rad"] = rounded(m.rotation_travelled_rad, 6);
  doc["final_true_pose"] = poseJson(m.final_truth);
  doc["final_odometry_pose"] = poseJson(m.final_odometry);
  doc["odometry_error"] = {{"position_m", rounded(m.odometry_position_error_m, 6)},
                           {"heading_rad", rounded(m.odometry_heading_error_rad, 6)},
                           {"heading_deg", rounded(radToDeg(m.odometry_heading_error_rad), 4)},
                           {"position_error_per_distance",
                            m.distance_travelled_m > 0.0
                                ? rounded(m.odometry_position_error_m / m.distance_travelled_m, 6)
                                : 0.0}};
  doc["explored_area_m2"] = rounded(m.explored_area_m2, 6);
  doc["sonar_readings"] = m.sonar_readings;
  doc["sonar_echoes"] = m.sonar_echoes;
  doc["bumper_events"] = m.bumper_events;
  return doc.dump(2) + "\n";
}

std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows) {
  std::string out =
      "time_s,true_x_m,true_y_m,true_theta_rad,odom_x_m,odom_y_m,odom_theta_rad,"
      "cmd_linear_mps,cmd_angular_radps,bumpers\n";
  out.reserve(rows.size() * 96);
  for (const TrajectoryRow& r : rows) {
    out += fixed(r.time_s, 3) + ',' + fixed(r.truth.x, 5) + ',' + fixed(r.truth.y, 5) + ',' +
           fixed(r.truth.theta, 5) + ',' + fixed(r.odometry.x, 5) + ',' + fixed(r.odometry.y, 5) +
           ',' + fixed(r.odometry.theta, 5) + ',' + fixed(r.command.linear_mps, 4) + ',' +
           fixed(r.command.angular_radps, 4) + ',' + std::to_string(r.bumpers) + '\n';
  }
  return out;
}

std::string gridPicturePng(const OccupancyGrid& grid, const std::vector<TrajectoryRow>& rows) {
  // The picture spans the observed grid plus the paths, with a small margin.
  const double res = grid.resolution_m();
  Box2 box = grid.observedBounds();
  for (const TrajectoryRow& r : rows) {
    box.extend(r.truth.position());
    box.extend(r.odometry.position());
  }
  if (box.empty())
    box.extend(Vec2::Zero());
  const Vec2 lo = box.min - Vec2(0.1, 0.1);
  const Vec2 hi = box.max + Vec2(0.1, 0.1);
  const int width = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / res)));
  const int height = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / res)));

  Picture picture(width, height);
  auto toPixel = [&](const Vec2& p) {
    return std::pair{static_cast<int>(std::floor((p.x() - lo.x()) / res)),
                     height - 1 - static_cast<int>(std::floor((p.y() - lo.y()) / res))};
  };
  for (int py = 0; py < height; ++py) {
    for (int px = 0; px < width; ++px) {
      const Vec2 centre(lo.x() + (px + 0.5) * res, lo.y() + (height - 1 - py + 0.5) * res);
      const Cell cell = grid.cellAt(centre);
      Rgb colour{205, 205, 205};  // unknown: the ROS map_server grey
      if (grid.observed(cell)) {
        const auto shade =
            static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - grid.probability(cell))));
        colour = {shade, shade, shade};
      }
      picture.set(px, py, colour);
    }
  }
  const int thickness = std::max(1, static_cast<int>(std::lround(0.02 / res)));
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto [ox0, oy0] = toPixel(rows[i - 1].odometry.position());
    const auto [ox1, oy1] = toPixel(rows[i].odometry.position());
    picture.line(ox0, oy0, ox1, oy1, {235, 130, 20}, thickness);
  }
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto [tx0, ty0] = toPixel(rows[i - 1].truth.position());
    const auto [tx1, ty1] = toPixel(rows[i].truth.position());
    picture.line(tx0, ty0, tx1, ty1, {30, 90, 220}, thickness);
  }
  return picture.png();
}

WriteOutputsResult writeScenarioOutputs(const ScenarioResult& result, const ScenarioRunInfo& info,
                                        const std::filesystem::path& out_dir) {
  WriteOutputsResult out;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    out.error = "cannot create output folder " + out_dir.string() + ": " + ec.message();
    return out;
  }
  auto write = [&](const std::string& name, const std::string& bytes) {
    const auto path = out_dir / name;
    if (auto error = writeFileAtomically(path, bytes)) {
      out.error = *error;
      return false;
    }
    out.written.push_back(path);
    return true;
  };

  const RasterMap raster = result.grid.toRaster();
  if (!raster.empty()) {
    if (auto error = saveRosMap(raster, out_dir / "grid.yaml")) {
      out.error = *error;
      return out;
    }
    out.written.push_back(out_dir / "grid.pgm");
    out.written.push_back(out_dir / "grid.yaml");
  }
  if (!write("grid.png", gridPicturePng(result.grid, result.trajectory)))
    return out;
  if (!write("metrics.json", metricsJson(result.metrics, info)))
    return out;
  if (!write("trajectory.csv", trajectoryCsv(result.trajectory)))
    return out;
  return out;
}

}  // namespace irgs
