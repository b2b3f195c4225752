#pragma once
// Frames from a real camera or a recording, through OpenCV (irgs_vision_io): an image file, a
// video file, or a V4L2 device. Opened from a location string:
//   "ceiling.png"            one image (png, jpg, bmp, ppm, tif): one frame
//   "run.mp4"                a video file (anything OpenCV's backends decode)
//   "/dev/video0", "v4l2:0"  a V4L2 camera, asked for width x height
// Frames come out as R, G, B RgbImage, ready for CeilingVision.

#include <memory>
#include <optional>
#include <string>

#include "core/camera/image.hpp"

namespace cv {
class VideoCapture;
}

namespace irgs::vision {

class FrameSource {
 public:
  struct OpenResult;
  // Opens `location`; `error` says why not. width/height are requested from cameras only.
  static OpenResult open(const std::string& location, int width_px = 640, int height_px = 480);

  FrameSource(FrameSource&&) noexcept;
  FrameSource& operator=(FrameSource&&) noexcept;
  ~FrameSource();

  // The next frame, nothing at the end of a file (an image gives one frame) or on a read error.
  std::optional<RgbImage> next();
  const std::string& location() const { return location_; }
  bool isDevice() const { return device_; }

 private:
  FrameSource() = default;
  std::string location_;
  bool device_ = false;
  std::optional<RgbImage> still_;  // an image file's single frame, until taken
  std::unique_ptr<cv::VideoCapture> capture_;
};

struct FrameSource::OpenResult {
  std::optional<FrameSource> source;
  std::string error;
};

// Writes `image` to `path` (format from the extension: png, jpg, ppm, ...); false on failure.
bool writeImage(const std::string& path, const RgbImage& image);

// "/dev/video3" -> 3, "v4l2:3" -> 3, "v4l2:///dev/video3" -> 3; nothing for other strings.
std::optional<int> v4l2DeviceIndex(const std::string& location);

}  // namespace irgs::vision
