#include "core/vision/image_convert.hpp"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace irgs::vision {

cv::Mat asRgbMat(const RgbImage& image) {
  // OpenCV does not write through this header; the const_cast only satisfies its constructor.
  return cv::Mat(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.data.data()),
                 static_cast<std::size_t>(image.stride));
}

RgbImage fromRgbMat(const cv::Mat& rgb) {
  if (rgb.type() != CV_8UC3)
    throw std::invalid_argument("fromRgbMat: expected CV_8UC3");
  RgbImage out(rgb.cols, rgb.rows);
  for (int y = 0; y < rgb.rows; ++y)
    std::copy_n(rgb.ptr<std::uint8_t>(y), 3 * rgb.cols, out.row(y));
  return out;
}

RgbImage fromBgrMat(const cv::Mat& bgr) {
  cv::Mat rgb;
  if (bgr.type() == CV_8UC1)
    cv::cvtColor(bgr, rgb, cv::COLOR_GRAY2RGB);
  else if (bgr.type() == CV_8UC3)
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  else if (bgr.type() == CV_8UC4)
    cv::cvtColor(bgr, rgb, cv::COLOR_BGRA2RGB);
  else
    throw std::invalid_argument("fromBgrMat: expected an 8-bit grey, BGR or BGRA image");
  return fromRgbMat(rgb);
}

}  // namespace irgs::vision
