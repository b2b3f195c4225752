#pragma once
// RgbImage (core) <-> cv::Mat. IRGS frames are R, G, B; OpenCV's own I/O is B, G, R, so the
// conversions name the order they produce.

#include <opencv2/core.hpp>

#include "core/camera/image.hpp"

namespace irgs::vision {

// A CV_8UC3 view (R, G, B) of `image`'s bytes: no copy, valid while `image` lives unchanged.
cv::Mat asRgbMat(const RgbImage& image);
// A copy of a CV_8UC3 R, G, B matrix. Throws std::invalid_argument for other types.
RgbImage fromRgbMat(const cv::Mat& rgb);
// A copy of a CV_8UC3 B, G, R matrix (what cv::imread and cv::VideoCapture deliver), or of a
// CV_8UC1 grey one.
RgbImage fromBgrMat(const cv::Mat& bgr);

}  // namespace irgs::vision
