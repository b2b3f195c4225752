#pragma once
// The camera panel (issue 7, item 5): what the ceiling camera sees (rendered in simulation, live
// from a camera otherwise), the metric top view, and the detections drawn over both. Qt and core
// only: the caller (app/gui/camera_controller) runs the OpenCV pipelines and hands over plain
// images and polygons in each image's pixel coordinates.

#include <QWidget>
#include <optional>
#include <string>
#include <vector>

#include "core/camera/image.hpp"
#include "core/geometry/types.hpp"

class QCheckBox;
class QLabel;
class QSpinBox;

namespace irgs::widgets {

// Shapes drawn over one image, in that image's pixels.
struct ImageOverlay {
  std::vector<std::vector<Vec2>> markers;   // accepted marker quadrilaterals (green)
  std::vector<std::vector<Vec2>> rejected;  // red regions that were not markers (orange, dashed)
  std::vector<std::vector<Vec2>> lights;    // labelled light regions (cyan)
  std::optional<Vec2> target;               // the light or marker being followed (cross)
  std::optional<Vec2> robot;                // the camera's position (top view)
};

struct CameraPanelFrame {
  RgbImage frame;
  ImageOverlay frame_overlay;
  RgbImage top_view;
  ImageOverlay top_overlay;
  double time_s = 0.0;
  double tilt_deg = 0.0;
  int markers = 0;
  int lights = 0;
  std::string source;  // "simulated", "/dev/video0", ...
};

// One image with its overlay, scaled to fit and centred, aspect kept.
class OverlayImageView : public QWidget {
  Q_OBJECT

 public:
  explicit OverlayImageView(const QString& title, QWidget* parent = nullptr);
  void setImage(const RgbImage& image, const ImageOverlay& overlay);
  void clear();
  bool hasImage() const { return !image_.isNull(); }
  QSize sizeHint() const override { return {320, 240}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  QString title_;
  QImage image_;
  ImageOverlay overlay_;
};

class CameraPanel : public QWidget {
  Q_OBJECT

 public:
  explicit CameraPanel(QWidget* parent = nullptr);

  void showFrame(const CameraPanelFrame& frame);
  // No frame to show, and why ("no ceiling in this map", "not in simulation", ...).
  void showMessage(const QString& text);

  // Tilt control: automatic (the tilt law of 002_…, from the landmark distance) or fixed.
  bool autoTilt() const;
  double fixedTiltDeg() const;
  void setFixedTiltDeg(double deg);

  OverlayImageView& frameView() const { return *frame_view_; }
  OverlayImageView& topView() const { return *top_view_; }
  QString statusText() const;

 signals:
  void tiltModeChanged(bool automatic, double fixed_deg);

 private:
  OverlayImageView* frame_view_ = nullptr;
  OverlayImageView* top_view_ = nullptr;
  QLabel* status_ = nullptr;
  QCheckBox* auto_tilt_ = nullptr;
  QSpinBox* tilt_ = nullptr;
};

// The image as a QImage (a deep copy).
QImage toQImage(const RgbImage& image);

}  // namespace irgs::widgets
