#include "core/vision/io/frame_source.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/vision/image_convert.hpp"

namespace irgs::vision {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool isStillImage(const std::string& location) {
  const std::string ext = lower(std::filesystem::path(location).extension().string());
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".ppm" ||
         ext == ".pgm" || ext == ".tif" || ext == ".tiff";
}

std::optional<int> digits(const std::string& s) {
  if (s.empty() || s.size() > 4 ||
      !std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
    return std::nullopt;
  return std::stoi(s);
}

}  // namespace

std::optional<int> v4l2DeviceIndex(const std::string& location) {
  std::string rest = location;
  if (rest.rfind("v4l2://", 0) == 0)
    rest = rest.substr(7);
  else if (rest.rfind("v4l2:", 0) == 0)
    rest = rest.substr(5);
  if (rest.rfind("/dev/video", 0) == 0)
    return digits(rest.substr(10));
  if (location.rfind("v4l2:", 0) == 0)
    return digits(rest);
  return std::nullopt;
}

FrameSource::OpenResult FrameSource::open(const std::string& location, int width_px,
                                          int height_px) {
  OpenResult result;
  FrameSource src;
  src.location_ = location;
  if (const auto index = v4l2DeviceIndex(location)) {
    src.device_ = true;
    src.capture_ = std::make_unique<cv::VideoCapture>(*index, cv::CAP_V4L2);
    if (!src.capture_->isOpened()) {
      result.error = "cannot open V4L2 device " + std::to_string(*index);
      return result;
    }
    src.capture_->set(cv::CAP_PROP_FRAME_WIDTH, width_px);
    src.capture_->set(cv::CAP_PROP_FRAME_HEIGHT, height_px);
  } else if (isStillImage(location)) {
    const cv::Mat bgr = cv::imread(location, cv::IMREAD_COLOR);
    if (bgr.empty()) {
      result.error = "cannot read image " + location;
      return result;
    }
    src.still_ = fromBgrMat(bgr);
  } else {
    if (!std::filesystem::exists(location)) {
      result.error = "no such file: " + location;
      return result;
    }
    src.capture_ = std::make_unique<cv::VideoCapture>(location);
    if (!src.capture_->isOpened()) {
      result.error = "cannot decode video " + location;
      return result;
    }
  }
  result.source = std::move(src);
  return result;
}

FrameSource::FrameSource(FrameSource&&) noexcept = default;
FrameSource& FrameSource::operator=(FrameSource&&) noexcept = default;
FrameSource::~FrameSource() = default;

bool writeImage(const std::string& path, const RgbImage& image) {
  cv::Mat bgr;
  cv::cvtColor(asRgbMat(image), bgr, cv::COLOR_RGB2BGR);
  try {
    return cv::imwrite(path, bgr);
  } catch (const cv::Exception&) {
    return false;
  }
}

std::optional<RgbImage> FrameSource::next() {
  if (still_) {
    std::optional<RgbImage> frame = std::move(still_);
    still_.reset();
    return frame;
  }
  if (!capture_)
    return std::nullopt;
  cv::Mat bgr;
  if (!capture_->read(bgr) || bgr.empty())
    return std::nullopt;
  return fromBgrMat(bgr);
}

}  // namespace irgs::vision
