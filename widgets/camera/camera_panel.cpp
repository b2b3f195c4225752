#include "widgets/camera/camera_panel.hpp"

#include <QCheckBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QPainterPath>
#include <QSpinBox>
#include <QVBoxLayout>

namespace irgs::widgets {
namespace {

const QColor kMarkerColour(40, 220, 60);
const QColor kRejectedColour(255, 150, 0);
const QColor kLightColour(0, 200, 255);
const QColor kTargetColour(255, 255, 0);

}  // namespace

QImage toQImage(const RgbImage& image) {
  if (image.empty())
    return {};
  const QImage view(image.data.data(), image.width, image.height, image.stride,
                    QImage::Format_RGB888);
  return view.copy();
}

OverlayImageView::OverlayImageView(const QString& title, QWidget* parent)
    : QWidget(parent), title_(title) {
  setMinimumSize(160, 120);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void OverlayImageView::setImage(const RgbImage& image, const ImageOverlay& overlay) {
  image_ = toQImage(image);
  overlay_ = overlay;
  update();
}

void OverlayImageView::clear() {
  image_ = QImage();
  overlay_ = {};
  update();
}

void OverlayImageView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(30, 30, 30));
  p.setRenderHint(QPainter::Antialiasing);
  const int title_h = fontMetrics().height() + 4;
  p.setPen(Qt::lightGray);
  p.drawText(QRect(4, 0, width() - 8, title_h), Qt::AlignLeft | Qt::AlignVCenter, title_);
  if (image_.isNull())
    return;
  const QRectF area(0, title_h, width(), height() - title_h);
  const double scale = std::min(area.width() / image_.width(), area.height() / image_.height());
  const QSizeF size(image_.width() * scale, image_.height() * scale);
  const QRectF target(area.center().x() - size.width() / 2, area.center().y() - size.height() / 2,
                      size.width(), size.height());
  p.drawImage(target, image_);
  // Image pixel centres are at integer coordinates: pixel (0, 0) covers [-0.5, 0.5].
  auto map = [&](const Vec2& px) {
    return QPointF(target.left() + (px.x() + 0.5) * scale, target.top() + (px.y() + 0.5) * scale);
  };
  auto polygon = [&](const std::vector<Vec2>& pts) {
    QPolygonF poly;
    for (const Vec2& v : pts)
      poly << map(v);
    return poly;
  };
  p.setBrush(Qt::NoBrush);
  p.setPen(QPen(kRejectedColour, 1.2, Qt::DashLine));
  for (const auto& r : overlay_.rejected)
    p.drawPolygon(polygon(r));
  p.setPen(QPen(kLightColour, 1.6));
  for (const auto& l : overlay_.lights)
    p.drawPolygon(polygon(l));
  p.setPen(QPen(kMarkerColour, 2.2));
  for (const auto& m : overlay_.markers)
    p.drawPolygon(polygon(m));
  if (overlay_.target) {
    const QPointF c = map(*overlay_.target);
    p.setPen(QPen(kTargetColour, 2.0));
    p.drawLine(c - QPointF(7, 0), c + QPointF(7, 0));
    p.drawLine(c - QPointF(0, 7), c + QPointF(0, 7));
  }
  if (overlay_.robot) {
    const QPointF c = map(*overlay_.robot);
    p.setPen(QPen(Qt::white, 1.5));
    p.setBrush(QColor(255, 255, 255, 90));
    // The robot seen from above, forward = up in the top view.
    QPolygonF tri;
    tri << c + QPointF(0, -9) << c + QPointF(-6, 6) << c + QPointF(6, 6);
    p.drawPolygon(tri);
  }
}

CameraPanel::CameraPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  auto* images = new QHBoxLayout;
  frame_view_ = new OverlayImageView(tr("Camera"), this);
  frame_view_->setObjectName(QStringLiteral("cameraFrameView"));
  top_view_ = new OverlayImageView(tr("Top view (metric, forward up)"), this);
  top_view_->setObjectName(QStringLiteral("cameraTopView"));
  images->addWidget(frame_view_, 4);
  images->addWidget(top_view_, 3);
  layout->addLayout(images, 1);
  auto* controls = new QHBoxLayout;
  auto_tilt_ = new QCheckBox(tr("Automatic tilt"), this);
  auto_tilt_->setObjectName(QStringLiteral("cameraAutoTilt"));
  auto_tilt_->setChecked(true);
  auto_tilt_->setToolTip(
      tr("Tilt the camera by the tilt law of the robot profile: 90° with the nearest marker "
         "overhead, 35° when it is far"));
  tilt_ = new QSpinBox(this);
  tilt_->setObjectName(QStringLiteral("cameraTilt"));
  tilt_->setRange(35, 90);
  tilt_->setValue(60);
  tilt_->setSuffix(QStringLiteral("°"));
  tilt_->setEnabled(false);
  tilt_->setToolTip(tr("Camera-to-ceiling angle: 90° looks straight up"));
  status_ = new QLabel(tr("No frame yet"), this);
  status_->setObjectName(QStringLiteral("cameraStatus"));
  controls->addWidget(auto_tilt_);
  controls->addWidget(new QLabel(tr("Tilt:"), this));
  controls->addWidget(tilt_);
  controls->addWidget(status_, 1);
  layout->addLayout(controls);
  connect(auto_tilt_, &QCheckBox::toggled, this, [this](bool on) {
    tilt_->setEnabled(!on);
    emit tiltModeChanged(on, tilt_->value());
  });
  connect(tilt_, &QSpinBox::valueChanged, this,
          [this](int v) { emit tiltModeChanged(auto_tilt_->isChecked(), v); });
}

void CameraPanel::showFrame(const CameraPanelFrame& f) {
  frame_view_->setImage(f.frame, f.frame_overlay);
  top_view_->setImage(f.top_view, f.top_overlay);
  status_->setText(tr("%1 · t = %2 s · tilt %3° · %4 marker(s) · %5 light(s)")
                       .arg(QString::fromStdString(f.source))
                       .arg(f.time_s, 0, 'f', 1)
                       .arg(f.tilt_deg, 0, 'f', 1)
                       .arg(f.markers)
                       .arg(f.lights));
  if (auto_tilt_->isChecked()) {
    const QSignalBlocker block(tilt_);
    tilt_->setValue(static_cast<int>(std::lround(f.tilt_deg)));
  }
}

void CameraPanel::showMessage(const QString& text) {
  frame_view_->clear();
  top_view_->clear();
  status_->setText(text);
}

bool CameraPanel::autoTilt() const {
  return auto_tilt_->isChecked();
}

double CameraPanel::fixedTiltDeg() const {
  return tilt_->value();
}

void CameraPanel::setFixedTiltDeg(double deg) {
  auto_tilt_->setChecked(false);
  tilt_->setValue(static_cast<int>(std::lround(deg)));
}

QString CameraPanel::statusText() const {
  return status_->text();
}

}  // namespace irgs::widgets
