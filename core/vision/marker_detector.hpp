#pragma once
// Ceiling-marker detection on the top view (002_… 3.5, Figs. 6-8): RGB -> YCbCr, Cr threshold,
// opening and closing, external contours, four vertices per contour (polygon approximation, or
// the minimum-area rectangle when the approximation does not give four), a metric size check
// (the top view is metric, so a marker is size_m wide at any distance), then normalised
// correlation of the candidate, rectified to a square, with the marker template. The centre is
// returned in the body frame, metres.

#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "core/navigation/ceiling_observation.hpp"
#include "core/vision/top_view.hpp"
#include "core/vision/vision_config.hpp"

namespace irgs::vision {

enum class CandidateVerdict { kAccepted, kTooSmall, kNotFourSided, kWrongSize, kPoorMatch };

// One red region looked at, kept for drawing and tuning.
struct MarkerCandidate {
  std::array<Vec2, 4> corners_top_px{};  // quadrilateral in top-view pixels
  Vec2 centre_body_m = Vec2::Zero();
  double mean_side_m = 0.0;
  double score = 0.0;
  CandidateVerdict verdict = CandidateVerdict::kTooSmall;
};

struct MarkerDetectionResult {
  std::vector<MarkerDetection> markers;     // accepted, nearest first
  std::vector<MarkerCandidate> candidates;  // every contour examined
};

class MarkerDetector {
 public:
  explicit MarkerDetector(const MarkerConfig& config, double px_per_m);

  // `top_view_rgb`: CV_8UC3 in R, G, B order, warped by `geometry`.
  MarkerDetectionResult detect(const cv::Mat& top_view_rgb, const TopViewGeometry& geometry) const;

  // The Cr mask after threshold and morphology (exposed for the GUI and tests).
  cv::Mat redMask(const cv::Mat& top_view_rgb) const;
  const cv::Mat& templateImage() const { return template_; }

 private:
  void crAndMask(const cv::Mat& top_view_rgb, cv::Mat& cr, cv::Mat& mask) const;

  MarkerConfig config_;
  double px_per_m_;
  cv::Mat template_;  // CV_32F: the marker (1) inside a ceiling margin (0)
};

}  // namespace irgs::vision
