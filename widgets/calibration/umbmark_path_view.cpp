#include "widgets/calibration/umbmark_path_view.hpp"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>

namespace irgs::widgets {

UmbmarkPathView::UmbmarkPathView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(240, 240);
  setAccessibleName(tr("UMBmark paths"));
}

void UmbmarkPathView::setTrials(std::vector<UmbmarkTrial> before, std::vector<UmbmarkTrial> after,
                                double side_m) {
  before_ = std::move(before);
  after_ = std::move(after);
  side_m_ = side_m;
  update();
}

void UmbmarkPathView::clear() {
  before_.clear();
  after_.clear();
  update();
}

void UmbmarkPathView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), palette().base());
  // World extent: the cw square lies at y <= 0, the ccw one at y >= 0, both at x in [0, L],
  // grown to every drawn path (a badly calibrated robot strays far).
  double x0 = 0.0, x1 = side_m_, y0 = -side_m_, y1 = side_m_;
  for (const auto* trials : {&before_, &after_})
    for (const UmbmarkTrial& t : *trials)
      for (const auto* path : {&t.true_path, &t.odometry_path})
        for (const Vec2& v : *path) {
          x0 = std::min(x0, v.x());
          x1 = std::max(x1, v.x());
          y0 = std::min(y0, v.y());
          y1 = std::max(y1, v.y());
        }
  const double margin = 0.08 * std::max(x1 - x0, y1 - y0);
  x0 -= margin;
  x1 += margin;
  y0 -= margin;
  y1 += margin;
  const double scale = std::min(width() / (x1 - x0), height() / (y1 - y0));
  const QPointF offset((width() - scale * (x1 - x0)) / 2.0, (height() - scale * (y1 - y0)) / 2.0);
  const auto map = [&](const Vec2& v) {
    return offset + QPointF((v.x() - x0) * scale, (y1 - v.y()) * scale);  // y up on screen
  };

  p.setPen(QPen(QColor(170, 170, 170), 1.0));
  for (double sign : {-1.0, 1.0}) {
    const Vec2 corners[] = {{0, 0}, {side_m_, 0}, {side_m_, sign * side_m_}, {0, sign * side_m_}};
    QPolygonF square;
    for (const Vec2& c : corners)
      square << map(c);
    p.drawPolygon(square);
  }
  const auto drawPath = [&](const std::vector<Vec2>& path, QColor colour, Qt::PenStyle style) {
    if (path.size() < 2)
      return;
    QPainterPath line(map(path.front()));
    for (std::size_t i = 1; i < path.size(); ++i)
      line.lineTo(map(path[i]));
    p.setPen(QPen(colour, 1.6, style));
    p.drawPath(line);
    p.setBrush(colour);
    p.drawEllipse(map(path.back()), 3.0, 3.0);
    p.setBrush(Qt::NoBrush);
  };
  const auto drawFirstOfEach = [&](const std::vector<UmbmarkTrial>& trials, QColor cw, QColor ccw,
                                   bool with_odometry) {
    bool seen_cw = false, seen_ccw = false;
    for (const UmbmarkTrial& t : trials) {
      const bool is_cw = t.direction == UmbmarkDirection::kClockwise;
      bool& seen = is_cw ? seen_cw : seen_ccw;
      if (seen)
        continue;
      seen = true;
      if (with_odometry)
        drawPath(t.odometry_path, (is_cw ? cw : ccw).lighter(140), Qt::DashLine);
      drawPath(t.true_path, is_cw ? cw : ccw, Qt::SolidLine);
    }
  };
  drawFirstOfEach(after_, QColor(30, 150, 60), QColor(30, 150, 60), false);
  drawFirstOfEach(before_, QColor(40, 90, 200), QColor(200, 50, 50), true);

  p.setPen(palette().text().color());
  p.drawText(rect().adjusted(6, 4, -6, -4), Qt::AlignTop | Qt::AlignLeft,
             before_.empty() ? tr("No runs yet")
                             : tr("blue cw, red ccw: true (solid), odometry (dashed)\n"
                                  "green: after correction"));
  p.setPen(QPen(palette().text().color(), 1.0));
  p.drawEllipse(map(Vec2::Zero()), 4.0, 4.0);  // the start
}

}  // namespace irgs::widgets
