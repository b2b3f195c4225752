#include "app/recording/session_dump.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace irgs::recording {

namespace {

// Shortest text that reads back to the same double.
std::string exact(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

std::string writeTrajectoryCsv(const std::vector<TrajectoryPoint>& points,
                               const std::string& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out)
    return "cannot write " + path;
  out << "t_s,x_m,y_m,theta_rad\n";
  for (const TrajectoryPoint& p : points)
    out << exact(p.t_s) << ',' << exact(p.pose.x) << ',' << exact(p.pose.y) << ','
        << exact(p.pose.theta) << '\n';
  out.flush();
  return out ? std::string() : "cannot write " + path;
}

std::string writeGridCsv(const OccupancyGrid& grid, const std::string& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out)
    return "cannot write " + path;
  out << "resolution_m," << exact(grid.resolution_m()) << '\n';
  const OccupancyGrid::CellRect rect = grid.observedCellRect();
  if (!rect.empty()) {
    std::vector<float> values;
    grid.copyLogOdds(rect, values);
    std::size_t i = 0;
    for (int row = rect.row0; row <= rect.row1; ++row) {
      for (int col = rect.col0; col <= rect.col1; ++col, ++i) {
        if (std::isnan(values[i]))
          continue;
        out << col << ',' << row << ',' << exact(static_cast<double>(values[i])) << '\n';
      }
    }
  }
  out.flush();
  return out ? std::string() : "cannot write " + path;
}

}  // namespace irgs::recording
