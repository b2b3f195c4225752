#pragma once
// Every threshold of the ceiling-landmark pipelines (002_… 3.4-3.5), with defaults that work on
// the rendered frames of core/camera at 640 x 480 (docs/landmark-navigation.md lists the
// measured recall and precision). Loadable from JSON: the same keys, every one optional.
//
//   { "top_view": { "px_per_m", "max_range_m", "max_half_width_m" },
//     "marker": { "size_m", "cr_threshold", "open_px", "close_px", "approx_epsilon",
//                 "size_tolerance", "min_fill", "template_px", "template_margin_px",
//                 "min_score" },
//     "light": { "darken", "threshold", "erode_px", "dilate_px", "min_area_m2" } }

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace irgs::vision {

struct TopViewConfig {
  double px_per_m = 100.0;        // metric scale of the top view (1 px = 1 cm)
  double max_range_m = 6.0;       // farthest ceiling point (ahead of the robot) warped
  double max_half_width_m = 3.0;  // widest lateral extent warped
};

struct MarkerConfig {
  double size_m = 0.2;           // side of the square (002_…: 20 cm)
  int cr_threshold = 160;        // Cr above this is "red" (fluorescent red: ~230, grey: ~128)
  int open_px = 3;               // opening removes speckles
  int close_px = 3;              // closing fills holes left by noise
  double approx_epsilon = 0.08;  // polygon approximation tolerance, fraction of the perimeter
  double size_tolerance = 0.3;   // each side within (1 +- tolerance) * size_m
  double min_fill = 0.8;         // contour area / quadrilateral area
  int template_px = 24;          // side of the marker in the template
  int template_margin_px = 8;    // ceiling around it in the template
  double min_score = 0.6;        // normalised correlation with the template
};

struct LightConfig {
  int darken = 70;            // grey levels subtracted first ("lower the overall brightness")
  int threshold = 170;        // then binarised at this level (together: grey >= 240)
  int erode_px = 5;           // removes reflections and afterimages
  int dilate_px = 11;         // joins the pieces of one lamp
  double min_area_m2 = 0.01;  // smaller labelled regions are ignored
};

struct VisionConfig {
  TopViewConfig top_view;
  MarkerConfig marker;
  LightConfig light;
};

struct VisionConfigResult {
  VisionConfig config;
  std::vector<std::string> errors;  // "field: message"; the config keeps defaults there
};

VisionConfigResult visionConfigFromJson(const nlohmann::json& object);
nlohmann::json visionConfigToJson(const VisionConfig& config);

}  // namespace irgs::vision
