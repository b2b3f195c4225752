#include "app/recording/rerun_output.hpp"

#include <QImage>
#include <QString>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/recording/session_dump.hpp"
#include "core/mapping/grid_export.hpp"

namespace irgs::recording {
namespace {

using nlohmann::ordered_json;

ordered_json parametersJson(const RerunParameters& p) {
  ordered_json j = ordered_json::object();
  for (const RerunParameterInfo& info : rerunParameters())
    j[info.name] = rerunParameterValue(p, info.name);
  return j;
}

ordered_json differenceJson(const TrajectoryDifference& d) {
  return {{"compared", d.compared},
          {"rms_position_m", d.rms_position_m},
          {"max_position_m", d.max_position_m},
          {"rms_heading_rad", d.rms_heading_rad},
          {"max_heading_rad", d.max_heading_rad},
          {"final_position_m", d.final_position_m},
          {"final_heading_rad", d.final_heading_rad}};
}

ordered_json agreementJson(const OccupiedAgreement& a) {
  return {{"precision", a.precision}, {"recall", a.recall}, {"f1", a.f1}};
}

ordered_json runJson(const RerunRun& run) {
  ordered_json j = {{"parameters", parametersJson(run.parameters)},
                    {"poses", run.trajectory.size()},
                    {"readings_integrated", run.mapping.integrated},
                    {"readings_skipped", run.mapping.skipped},
                    {"observed_cells", run.grid.observedCellCount()},
                    {"explored_area_m2", run.grid.exploredArea_m2()}};
  j["truth_error"] = run.truth_error ? differenceJson(*run.truth_error) : ordered_json();
  return j;
}

// ROS map_server colours: occupied black, free white, unknown grey; row 0 at the top (+y up).
QImage gridImage(const OccupancyGrid& grid) {
  const RasterMap raster = rasterFromGrid(grid);
  QImage image(raster.width, raster.height, QImage::Format_Grayscale8);
  for (int row = 0; row < raster.height; ++row) {
    uchar* line = image.scanLine(raster.height - 1 - row);
    for (int col = 0; col < raster.width; ++col) {
      const int v = raster.cells[static_cast<std::size_t>(row) * raster.width + col];
      line[col] = static_cast<uchar>(v < 0 ? 205 : (v >= 50 ? 0 : 254));
    }
  }
  return image;
}

std::string writeTrajectory(const std::vector<RerunPose>& trajectory,
                            const std::filesystem::path& path) {
  std::FILE* f = std::fopen(path.string().c_str(), "w");
  if (f == nullptr)
    return "cannot write " + path.string();
  std::fprintf(f,
               "recording_t_s,robot_t_s,odom_x,odom_y,odom_theta,x,y,theta,truth_x,truth_y,"
               "truth_theta\n");
  for (const RerunPose& p : trajectory) {
    std::fprintf(f, "%.6f,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", p.recording_t_s, p.robot_t_s,
                 p.odometry.x, p.odometry.y, p.odometry.theta, p.pose.x, p.pose.y, p.pose.theta);
    if (p.truth)
      std::fprintf(f, ",%.9g,%.9g,%.9g\n", p.truth->x, p.truth->y, p.truth->theta);
    else
      std::fprintf(f, ",,,\n");
  }
  const bool ok = std::fclose(f) == 0;
  return ok ? std::string() : "cannot write " + path.string();
}

std::string writeGrid(const OccupancyGrid& grid, const std::filesystem::path& dir,
                      const std::string& stem) {
  // Every observed cell's log-odds, as irgs --grid-out writes them (comparable with a GUI run).
  if (std::string e = writeGridCsv(grid, (dir / (stem + "_grid.csv")).string()); !e.empty())
    return e;
  if (grid.observedCellCount() == 0)
    return {};  // nothing mapped: no image, no ROS map (map_server needs cells)
  if (const auto error = saveGridAsRosMap(grid, dir / (stem + "_map.yaml")))
    return *error;
  const std::filesystem::path png = dir / (stem + "_map.png");
  if (!gridImage(grid).save(QString::fromStdString(png.string()), "PNG"))
    return "cannot write " + png.string();
  return {};
}

}  // namespace

std::string rerunMetricsJson(const RerunResult& result, const std::string& recording_name) {
  const GridComparison& g = result.metrics.grid;
  ordered_json changed = ordered_json::array();
  for (const std::string& name :
       changedRerunParameters(result.recorded.parameters, result.rerun.parameters))
    changed.push_back(name);
  ordered_json j = {
      {"recording", recording_name},
      {"samples", result.samples},
      {"changed_parameters", changed},
      {"decode",
       {{"chunks", result.decode.chunks},
        {"bytes", result.decode.bytes},
        {"frames", result.decode.decoder.frames},
        {"bad_crc", result.decode.decoder.bad_crc},
        {"garbage_bytes", result.decode.decoder.garbage_bytes},
        {"link_ups", result.decode.link_ups},
        {"sonar_readings", result.decode.assembler.sonar_readings},
        {"restarts", result.decode.assembler.restarts}}},
      {"recorded", runJson(result.recorded)},
      {"rerun", runJson(result.rerun)},
      {"grid",
       {{"resolution_m", g.resolution_m},
        {"identical", g.identical},
        {"compared_cells", g.compared_cells},
        {"same_class_cells", g.same_class_cells},
        {"agreement", g.agreement},
        {"recorded_only_cells", g.reference_only},
        {"rerun_only_cells", g.candidate_only},
        {"recorded_occupied_cells", g.reference_occupied},
        {"rerun_occupied_cells", g.candidate_occupied},
        {"occupied", agreementJson(g.occupied)},
        {"occupied_tolerant", agreementJson(g.occupied_tolerant)}}},
      {"pose", differenceJson(result.metrics.pose)},
  };
  return j.dump(2) + "\n";
}

std::string writeRerunOutputs(const RerunResult& result, const std::filesystem::path& dir,
                              const std::string& recording_name) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    return "cannot create " + dir.string() + ": " + ec.message();
  for (const auto& [run, stem] :
       {std::pair{&result.recorded, "recorded"}, std::pair{&result.rerun, "rerun"}}) {
    if (std::string e = writeGrid(run->grid, dir, std::string(stem)); !e.empty())
      return e;
    if (std::string e =
            writeTrajectory(run->trajectory, dir / (std::string(stem) + "_trajectory.csv"));
        !e.empty())
      return e;
  }
  std::ofstream json(dir / "metrics.json");
  json << rerunMetricsJson(result, recording_name);
  json.close();
  if (!json)
    return "cannot write " + (dir / "metrics.json").string();
  return {};
}

}  // namespace irgs::recording
