#include "widgets/plots/plot_panel.hpp"

#include <QContextMenuEvent>
#include <QDragEnterEvent>
#include <QFile>
#include <QFileDialog>
#include <QImage>
#include <QInputDialog>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QPainterPath>
#include <QTextStream>
#include <QWheelEvent>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <set>

#include "widgets/plots/plot_data_hub.hpp"

namespace irgs::widgets {
namespace {

// Distinct on white, colour-blind friendly first (Okabe-Ito), then darker extras.
const std::array<QColor, 12> kPalette{
    {QColor(0, 114, 178), QColor(213, 94, 0), QColor(0, 158, 115), QColor(204, 121, 167),
     QColor(230, 159, 0), QColor(86, 180, 233), QColor(0, 0, 0), QColor(153, 0, 0),
     QColor(0, 90, 50), QColor(120, 60, 160), QColor(140, 110, 0), QColor(90, 90, 90)}};

constexpr int kLegendRow_px = 16;
constexpr int kAxisLeft_px = 58;
constexpr int kAxisBottom_px = 18;
constexpr int kMargin_px = 6;

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `target` ticks over `span`.
double niceStep(double span, int target) {
  if (!(span > 0.0))
    return 1.0;
  const double raw = span / std::max(target, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / power;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * power;
}

QString formatValue(double v) {
  const double a = std::abs(v);
  if (a != 0.0 && (a >= 1e5 || a < 1e-3))
    return QString::number(v, 'e', 2);
  return QString::number(v, 'g', 4);
}

// The key without its source: "Odometry pose x", "DISTANCE_SENSOR id 0 current_distance".
QString lastComponent(const QString& key) {
  const QStringList parts = key.split(QLatin1Char('/'));
  if (parts.size() >= 3)
    return parts.mid(1).join(QLatin1Char(' '));
  return parts.size() == 2 ? parts[0] + QLatin1Char(' ') + parts[1] : key;
}

// "Group name [unit]", or the whole key when another trace of the panel has the same short
// name (telemetry and command velocity).
QString legendText(const PlotTrace& trace, const std::vector<PlotTrace>& all) {
  const QString short_name = lastComponent(trace.key);
  const auto same = std::count_if(all.begin(), all.end(), [&](const PlotTrace& other) {
    return lastComponent(other.key) == short_name;
  });
  const QString name = same > 1 ? trace.key : short_name;
  return trace.display_unit.isEmpty() ? name
                                      : QStringLiteral("%1 [%2]").arg(name, trace.display_unit);
}

// The y interval for data spanning `all`: 5 % padding; a flat or empty signal gets a small span.
PlotRange fitY(const std::optional<PlotRange>& all) {
  if (!all)
    return {-1.0, 1.0};
  double span = all->max - all->min;
  if (span <= 1e-12 * std::max(1.0, std::abs(all->max)))
    span = std::max(std::abs(all->max) * 0.1, 1e-6);
  const double pad = 0.05 * span;
  return {all->min - pad, all->max + pad};
}

}  // namespace

PlotTrace defaultTrace(const QString& key, const QString& unit, const QColor& colour) {
  PlotTrace trace{key, colour, 1.0, unit};
  if (unit == QStringLiteral("rad")) {
    trace.scale = 180.0 / std::numbers::pi;
    trace.display_unit = QStringLiteral("deg");
  } else if (unit == QStringLiteral("rad/s")) {
    trace.scale = 180.0 / std::numbers::pi;
    trace.display_unit = QStringLiteral("deg/s");
  }
  return trace;
}

PlotPanel::PlotPanel(PlotDataHub& hub, QWidget* parent) : QWidget(parent), hub_(hub) {
  setAcceptDrops(true);
  setFocusPolicy(Qt::ClickFocus);
  setAttribute(Qt::WA_OpaquePaintEvent);
  setToolTip(
      tr("Drop fields here. Wheel: zoom time; drag: pan (pauses); double-click: live; "
         "right-click: traces, scale, export"));
}

PlotPanel::~PlotPanel() = default;

bool PlotPanel::addField(const QString& key) {
  if (!hub_.contains(key))
    return false;
  if (std::any_of(traces_.begin(), traces_.end(), [&](const PlotTrace& t) { return t.key == key; }))
    return false;
  traces_.push_back(
      defaultTrace(key, hub_.unit(key), kPalette[static_cast<std::size_t>(next_colour_)]));
  next_colour_ = (next_colour_ + 1) % static_cast<int>(kPalette.size());
  dirty_ = true;
  update();
  emit tracesChanged();
  return true;
}

bool PlotPanel::removeField(const QString& key) {
  const auto it = std::find_if(traces_.begin(), traces_.end(),
                               [&](const PlotTrace& t) { return t.key == key; });
  if (it == traces_.end())
    return false;
  traces_.erase(it);
  dirty_ = true;
  update();
  emit tracesChanged();
  return true;
}

void PlotPanel::clearFields() {
  traces_.clear();
  next_colour_ = 0;
  dirty_ = true;
  update();
  emit tracesChanged();
}

bool PlotPanel::setTraceScale(const QString& key, double scale, const QString& display_unit) {
  if (!std::isfinite(scale) || scale == 0.0)
    return false;
  for (PlotTrace& t : traces_) {
    if (t.key == key) {
      t.scale = scale;
      t.display_unit = display_unit;
      dirty_ = true;
      update();
      return true;
    }
  }
  return false;
}

void PlotPanel::setWindow_s(double window_s) {
  if (!std::isfinite(window_s))
    return;
  window_s_ = std::clamp(window_s, kMinWindow_s, kMaxWindow_s);
  dirty_ = true;
  update();
}

void PlotPanel::setPaused(bool paused) {
  if (paused == paused_)
    return;
  if (paused)
    paused_end_s_ = hub_.latestTime_s();
  paused_ = paused;
  dirty_ = true;
  update();
  emit pausedChanged(paused_);
}

std::pair<double, double> PlotPanel::visibleTime() const {
  const double end = paused_ ? paused_end_s_ : hub_.latestTime_s();
  return {end - window_s_, end};
}

void PlotPanel::setYRange(std::optional<PlotRange> range) {
  if (range && !(range->max > range->min))
    return;
  fixed_y_ = range;
  dirty_ = true;
  update();
}

std::optional<PlotRange> PlotPanel::visibleRange(const QString& key) const {
  const PlotSeries* series = hub_.series(key);
  const auto trace = std::find_if(traces_.begin(), traces_.end(),
                                  [&](const PlotTrace& t) { return t.key == key; });
  if (series == nullptr || trace == traces_.end())
    return std::nullopt;
  const auto [t0, t1] = visibleTime();
  std::optional<PlotRange> r = series->range(t0, t1);
  if (r) {
    const double a = r->min * trace->scale;
    const double b = r->max * trace->scale;
    r = PlotRange{std::min(a, b), std::max(a, b)};
  }
  return r;
}

PlotRange PlotPanel::visibleY() const {
  if (fixed_y_)
    return *fixed_y_;
  std::optional<PlotRange> all;
  for (const PlotTrace& t : traces_) {
    if (const auto r = visibleRange(t.key)) {
      all = all ? PlotRange{std::min(all->min, r->min), std::max(all->max, r->max)} : *r;
    }
  }
  return fitY(all);
}

void PlotPanel::setCurrent(bool current) {
  if (current_ == current)
    return;
  current_ = current;
  update();
}

void PlotPanel::refresh() {
  if (!isVisible())
    return;
  if (dirty_ || (!paused_ && hub_.revision() != drawn_revision_))
    update();
}

QRect PlotPanel::plotRect() const {
  return rect();
}

void PlotPanel::paintEvent(QPaintEvent* /*event*/) {
  QPainter painter(this);
  paintTo(painter, rect());
  drawn_revision_ = hub_.revision();
  dirty_ = false;
}

void PlotPanel::paintTo(QPainter& painter, const QRect& area) const {
  painter.fillRect(area, Qt::white);
  const QFontMetrics fm = painter.fontMetrics();

  // Legend: entries flow left to right, as many rows as needed.
  struct LegendEntry {
    QString text;
    QColor colour;
  };
  // One decimation per trace and frame: the columns keep every extreme, so the legend's min/max
  // and the fitted y axis come from them too (no second pass over the samples).
  const auto [t0, t1] = visibleTime();
  const int columns_px = std::max(10, area.width() - kAxisLeft_px - kMargin_px * 2);
  std::vector<std::vector<PlotColumn>> columns(traces_.size());
  std::vector<std::optional<PlotRange>> ranges(traces_.size());
  std::optional<PlotRange> all;
  for (std::size_t i = 0; i < traces_.size(); ++i) {
    const PlotSeries* series = hub_.series(traces_[i].key);
    if (series == nullptr)
      continue;
    columns[i] = series->decimate(t0, t1, columns_px);
    if (columns[i].empty())
      continue;
    double lo = columns[i].front().min;
    double hi = columns[i].front().max;
    for (const PlotColumn& c : columns[i]) {
      lo = std::min(lo, c.min);
      hi = std::max(hi, c.max);
    }
    const double a = lo * traces_[i].scale;
    const double b = hi * traces_[i].scale;
    ranges[i] = PlotRange{std::min(a, b), std::max(a, b)};
    all = all ? PlotRange{std::min(all->min, ranges[i]->min), std::max(all->max, ranges[i]->max)}
              : *ranges[i];
  }
  std::vector<LegendEntry> entries;
  for (std::size_t i = 0; i < traces_.size(); ++i) {
    const PlotTrace& t = traces_[i];
    QString text = legendText(t, traces_);
    const PlotSeries* series = hub_.series(t.key);
    if (series != nullptr && !series->empty()) {
      text += QStringLiteral("  %1").arg(formatValue(series->newest().value * t.scale));
      if (const auto& r = ranges[i])
        text += QStringLiteral("  (min %1, max %2)").arg(formatValue(r->min), formatValue(r->max));
    }
    entries.push_back({text, t.colour});
  }
  int legend_x = area.left() + kMargin_px;
  int legend_y = area.top() + kMargin_px;
  int rows = 1;
  std::vector<QPoint> positions;
  for (const LegendEntry& e : entries) {
    const int entry_w = 14 + fm.horizontalAdvance(e.text) + 12;
    if (legend_x + entry_w > area.right() - kMargin_px && legend_x > area.left() + kMargin_px) {
      legend_x = area.left() + kMargin_px;
      legend_y += kLegendRow_px;
      ++rows;
    }
    positions.emplace_back(legend_x, legend_y);
    legend_x += entry_w;
  }
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const QPoint p = positions[i];
    painter.fillRect(QRect(p.x(), p.y() + 4, 10, 8), entries[i].colour);
    painter.setPen(Qt::black);
    painter.drawText(QPoint(p.x() + 14, p.y() + fm.ascent()), entries[i].text);
  }
  if (entries.empty()) {
    painter.setPen(QColor(120, 120, 120));
    painter.drawText(QPoint(area.left() + kMargin_px, area.top() + kMargin_px + fm.ascent()),
                     tr("Drag fields here from the field browser (or double-click a field)"));
  }
  const int legend_h = rows * kLegendRow_px + kMargin_px;
  const QRect plot(area.left() + kAxisLeft_px, area.top() + legend_h + kMargin_px, columns_px,
                   std::max(10, area.height() - legend_h - kAxisBottom_px - kMargin_px * 2));
  const PlotRange yr = fixed_y_ ? *fixed_y_ : fitY(all);
  const double sx = plot.width() / (t1 - t0);
  const double sy = plot.height() / (yr.max - yr.min);
  auto px = [&](double t) { return plot.left() + (t - t0) * sx; };
  auto py = [&](double v) { return plot.bottom() - (v - yr.min) * sy; };

  // Grid and tick labels.
  painter.setPen(QColor(225, 225, 225));
  const double ystep = niceStep(yr.max - yr.min, std::max(2, plot.height() / 40));
  const double tstep = niceStep(t1 - t0, std::max(2, plot.width() / 90));
  for (double v = std::ceil(yr.min / ystep) * ystep; v <= yr.max; v += ystep) {
    const int yy = static_cast<int>(std::lround(py(v)));
    painter.setPen(QColor(225, 225, 225));
    painter.drawLine(plot.left(), yy, plot.right(), yy);
    painter.setPen(QColor(60, 60, 60));
    const QString label = formatValue(std::abs(v) < ystep * 1e-6 ? 0.0 : v);
    painter.drawText(QRect(area.left(), yy - 8, kAxisLeft_px - 4, 16),
                     Qt::AlignRight | Qt::AlignVCenter, label);
  }
  for (double t = std::ceil(t0 / tstep) * tstep; t <= t1; t += tstep) {
    const int xx = static_cast<int>(std::lround(px(t)));
    painter.setPen(QColor(225, 225, 225));
    painter.drawLine(xx, plot.top(), xx, plot.bottom());
    painter.setPen(QColor(60, 60, 60));
    painter.drawText(
        QRect(xx - 40, plot.bottom() + 2, 80, kAxisBottom_px), Qt::AlignHCenter | Qt::AlignTop,
        QString::number(std::abs(t) < tstep * 1e-6 ? 0.0 : t, 'g', 6) + QStringLiteral(" s"));
  }
  painter.setPen(QColor(150, 150, 150));
  painter.drawRect(plot.adjusted(0, 0, -1, -1));

  // Traces from the decimated columns, rasterised straight into an image the size of the plot:
  // per column a vertical span min..max, joined to the previous column's last value by a line.
  // The same 1-px picture as a polyline through first/min/max/last of every column, at a
  // fraction of the cost of QPainter stroking ~5 600 short segments per trace (measured with
  // irgs-plot-frame-bench, docs/performance.md).
  QImage layer(plot.size(), QImage::Format_ARGB32_Premultiplied);
  layer.fill(Qt::transparent);
  const int w = layer.width();
  const int h = layer.height();
  auto put = [&](int x, int y, QRgb rgb) {
    if (x >= 0 && x < w && y >= 0 && y < h)
      reinterpret_cast<QRgb*>(layer.scanLine(y))[x] = rgb;
  };
  auto toPx = [&](double t) { return static_cast<int>(std::floor((t - t0) * sx)); };
  auto toPy = [&](double v) {
    const double y = (yr.max - v) * sy;
    return static_cast<int>(std::floor(std::clamp(y, -1.0, static_cast<double>(h))));
  };
  for (std::size_t i = 0; i < traces_.size(); ++i) {
    const PlotTrace& t = traces_[i];
    const QRgb rgb = t.colour.rgba();
    std::optional<QPoint> previous;
    for (const PlotColumn& c : columns[i]) {
      const int x = toPx(c.time_s);
      const int y_first = toPy(c.first * t.scale);
      if (previous) {
        // Bresenham from the previous column's last value to this column's first.
        int x0 = previous->x();
        int y0 = previous->y();
        const int dx = std::abs(x - x0);
        const int dy = -std::abs(y_first - y0);
        const int step_x = x0 < x ? 1 : -1;
        const int step_y = y0 < y_first ? 1 : -1;
        int error = dx + dy;
        for (;;) {
          put(x0, y0, rgb);
          if (x0 == x && y0 == y_first)
            break;
          const int e2 = 2 * error;
          if (e2 >= dy) {
            error += dy;
            x0 += step_x;
          }
          if (e2 <= dx) {
            error += dx;
            y0 += step_y;
          }
        }
      }
      const int ya = toPy(c.min * t.scale);
      const int yb = toPy(c.max * t.scale);
      if (x >= 0 && x < w) {
        for (int y = std::max(0, std::min({ya, yb, y_first}));
             y <= std::min(h - 1, std::max({ya, yb, y_first})); ++y)
          reinterpret_cast<QRgb*>(layer.scanLine(y))[x] = rgb;
      }
      previous = QPoint(x, toPy(c.last * t.scale));
    }
  }
  painter.drawImage(plot.topLeft(), layer);

  if (paused_) {
    painter.setPen(QColor(180, 0, 0));
    painter.drawText(plot.adjusted(4, 2, -4, -2), Qt::AlignRight | Qt::AlignTop, tr("paused"));
  }
  if (current_) {
    painter.setPen(QPen(QColor(0, 114, 178), 2));
    painter.drawRect(area.adjusted(1, 1, -1, -1));
  }
}

void PlotPanel::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasFormat(QString::fromLatin1(kFieldMimeType)))
    event->acceptProposedAction();
}

void PlotPanel::dragMoveEvent(QDragMoveEvent* event) {
  if (event->mimeData()->hasFormat(QString::fromLatin1(kFieldMimeType)))
    event->acceptProposedAction();
}

void PlotPanel::dropEvent(QDropEvent* event) {
  const QByteArray payload = event->mimeData()->data(QString::fromLatin1(kFieldMimeType));
  bool any = false;
  for (const QString& key : QString::fromUtf8(payload).split(QLatin1Char('\n'), Qt::SkipEmptyParts))
    any = addField(key) || any;
  if (any || !payload.isEmpty())
    event->acceptProposedAction();
  emit activated(this);
}

void PlotPanel::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  if (steps == 0.0)
    return;
  const auto [t0, t1] = visibleTime();
  const double factor = std::pow(0.8, steps);
  const double new_window = std::clamp(window_s_ * factor, kMinWindow_s, kMaxWindow_s);
  if (paused_) {
    // Zoom about the time under the cursor.
    const QRect r = rect().adjusted(kAxisLeft_px, 0, -kMargin_px, 0);
    const double frac =
        std::clamp((event->position().x() - r.left()) / std::max(1, r.width()), 0.0, 1.0);
    const double at = t0 + frac * (t1 - t0);
    paused_end_s_ = at + (1.0 - frac) * new_window;
  }
  window_s_ = new_window;
  dirty_ = true;
  update();
  event->accept();
}

void PlotPanel::mousePressEvent(QMouseEvent* event) {
  emit activated(this);
  if (event->button() == Qt::LeftButton) {
    drag_from_ = event->pos();
    drag_end_s_ = visibleTime().second;
  }
}

void PlotPanel::mouseMoveEvent(QMouseEvent* event) {
  if (!drag_from_ || !(event->buttons() & Qt::LeftButton))
    return;
  const int dx = event->pos().x() - drag_from_->x();
  if (std::abs(dx) < 3 && !paused_)
    return;
  const double per_px = window_s_ / std::max(1, width() - kAxisLeft_px - kMargin_px * 2);
  setPaused(true);
  paused_end_s_ = drag_end_s_ - dx * per_px;
  dirty_ = true;
  update();
}

void PlotPanel::mouseReleaseEvent(QMouseEvent* /*event*/) {
  drag_from_.reset();
}

void PlotPanel::mouseDoubleClickEvent(QMouseEvent* /*event*/) {
  setPaused(false);
}

void PlotPanel::contextMenuEvent(QContextMenuEvent* event) {
  emit activated(this);
  QMenu menu(this);
  QAction* pause = menu.addAction(paused_ ? tr("&Resume (live)") : tr("&Pause"));
  connect(pause, &QAction::triggered, this, [this] { setPaused(!paused_); });
  if (!traces_.empty()) {
    QMenu* scale = menu.addMenu(tr("&Scale"));
    QMenu* remove = menu.addMenu(tr("&Remove"));
    for (const PlotTrace& t : traces_) {
      const QString key = t.key;
      connect(scale->addAction(key), &QAction::triggered, this, [this, key] { askScale(key); });
      connect(remove->addAction(key), &QAction::triggered, this, [this, key] { removeField(key); });
    }
    connect(menu.addAction(tr("Remove &All")), &QAction::triggered, this, &PlotPanel::clearFields);
  }
  menu.addSeparator();
  connect(menu.addAction(tr("Export &CSV…")), &QAction::triggered, this, &PlotPanel::chooseCsv);
  connect(menu.addAction(tr("Export P&NG…")), &QAction::triggered, this, &PlotPanel::choosePng);
  menu.exec(event->globalPos());
}

void PlotPanel::askScale(const QString& key) {
  const auto it = std::find_if(traces_.begin(), traces_.end(),
                               [&](const PlotTrace& t) { return t.key == key; });
  if (it == traces_.end())
    return;
  bool ok = false;
  const double scale =
      QInputDialog::getDouble(this, tr("Scale %1").arg(key),
                              tr("Displayed value = recorded value (%1) ×").arg(hub_.unit(key)),
                              it->scale, -1e12, 1e12, 6, &ok);
  if (!ok)
    return;
  const QString unit = QInputDialog::getText(this, tr("Unit of %1").arg(key), tr("Displayed unit:"),
                                             QLineEdit::Normal, it->display_unit, &ok);
  if (ok)
    setTraceScale(key, scale, unit);
}

QString PlotPanel::exportCsv(const QString& path) const {
  const auto [t0, t1] = visibleTime();
  std::vector<std::vector<PlotSample>> columns;
  std::set<double> times;
  for (const PlotTrace& t : traces_) {
    const PlotSeries* series = hub_.series(t.key);
    columns.push_back(series != nullptr ? series->samples(t0, t1) : std::vector<PlotSample>{});
    for (const PlotSample& s : columns.back())
      times.insert(s.time_s);
  }
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate | QIODevice::Text))
    return tr("cannot write %1: %2").arg(path, file.errorString());
  QTextStream out(&file);
  out << "time_s";
  for (const PlotTrace& t : traces_) {
    QString header =
        t.display_unit.isEmpty() ? t.key : QStringLiteral("%1 [%2]").arg(t.key, t.display_unit);
    header.replace(QLatin1Char('"'), QStringLiteral("\"\""));
    out << ",\"" << header << '"';
  }
  out << '\n';
  std::vector<std::size_t> next(columns.size(), 0);
  for (const double time : times) {
    out << QString::number(time, 'g', 12);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      out << ',';
      if (next[c] < columns[c].size() && columns[c][next[c]].time_s == time) {
        out << QString::number(columns[c][next[c]].value * traces_[c].scale, 'g', 10);
        ++next[c];
      }
    }
    out << '\n';
  }
  out.flush();
  if (file.error() != QFile::NoError)
    return tr("cannot write %1: %2").arg(path, file.errorString());
  return {};
}

QString PlotPanel::exportPng(const QString& path, QSize size) const {
  if (size.isEmpty())
    size = this->size();
  if (size.isEmpty())
    size = QSize(800, 400);
  QImage image(size, QImage::Format_ARGB32_Premultiplied);
  {
    QPainter painter(&image);
    painter.setFont(font());
    paintTo(painter, QRect(QPoint(0, 0), size));
  }
  if (!image.save(path, "PNG"))
    return tr("cannot write %1").arg(path);
  return {};
}

void PlotPanel::chooseCsv() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export Plot as CSV"),
                                                    QStringLiteral("plot.csv"), tr("CSV (*.csv)"));
  if (path.isEmpty())
    return;
  if (const QString error = exportCsv(path); !error.isEmpty())
    QMessageBox::warning(this, tr("Export CSV"), error);
}

void PlotPanel::choosePng() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export Plot as PNG"),
                                                    QStringLiteral("plot.png"), tr("PNG (*.png)"));
  if (path.isEmpty())
    return;
  if (const QString error = exportPng(path); !error.isEmpty())
    QMessageBox::warning(this, tr("Export PNG"), error);
}

}  // namespace irgs::widgets
