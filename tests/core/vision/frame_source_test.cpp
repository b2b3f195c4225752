#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "core/camera/ceiling_renderer.hpp"
#include "core/vision/ceiling_vision.hpp"
#include "core/vision/io/frame_source.hpp"

namespace irgs::vision {
namespace {

TEST(FrameSource, RecognisesV4l2Locations) {
  EXPECT_EQ(v4l2DeviceIndex("/dev/video0"), 0);
  EXPECT_EQ(v4l2DeviceIndex("v4l2:2"), 2);
  EXPECT_EQ(v4l2DeviceIndex("v4l2:///dev/video3"), 3);
  EXPECT_FALSE(v4l2DeviceIndex("frame.png"));
  EXPECT_FALSE(v4l2DeviceIndex("/dev/videox"));
}

TEST(FrameSource, AMissingFileIsAnError) {
  EXPECT_FALSE(FrameSource::open("/nonexistent/ceiling.png").source);
  EXPECT_FALSE(FrameSource::open("/nonexistent/run.avi").source);
}

TEST(FrameSource, AnImageFileGivesOneFrameThePipelinesRead) {
  // A rendered frame written as PNG (the format a real camera's stills would come in), read back
  // through OpenCV's codecs and processed like a live frame.
  const CeilingView view(CameraIntrinsics{}, CameraMount{0.0, 0.0, 0.5}, 2.5, degToRad(90.0));
  CeilingScene scene;
  scene.ceiling_height_m = 2.5;
  scene.markers.push_back({Vec2(0.4, -0.2), 0.2, 0.2, 0.2});
  const RgbImage frame = renderCeiling(view, scene, Pose2{}, RenderSettings{});
  const auto path = std::filesystem::temp_directory_path() / "irgs_frame_source_test.png";
  ASSERT_TRUE(writeImage(path.string(), frame));
  auto opened = FrameSource::open(path.string());
  ASSERT_TRUE(opened.source) << opened.error;
  const auto read = opened.source->next();
  ASSERT_TRUE(read);
  EXPECT_EQ(*read, frame);  // PNG is lossless
  EXPECT_FALSE(opened.source->next());
  const CeilingVisionResult r = CeilingVision().process(*read, view);
  ASSERT_EQ(r.markers.markers.size(), 1u);
  EXPECT_LT((r.markers.markers[0].centre_body_m - Vec2(0.4, -0.2)).norm(), 0.02);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace irgs::vision
