// Must NOT compile: irgs_core does not provide OpenCV (see tests/layering/CMakeLists.txt).
#include <opencv2/core.hpp>

int main() {
  return cv::Mat::eye(2, 2, CV_8U).empty() ? 1 : 0;
}
