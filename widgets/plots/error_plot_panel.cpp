#include "widgets/plots/error_plot_panel.hpp"

#include <QChart>
#include <QChartView>
#include <QFile>
#include <QFileDialog>
#include <QGraphicsScene>
#include <QHBoxLayout>
#include <QLabel>
#include <QLegend>
#include <QLegendMarker>
#include <QLineSeries>
#include <QPainter>
#include <QPen>
#include <QPixmap>
#include <QPushButton>
#include <QTabWidget>
#include <QTextStream>
#include <QTimer>
#include <QVBoxLayout>
#include <QValueAxis>
#include <algorithm>
#include <cmath>

#include "core/geometry/types.hpp"

namespace irgs::widgets {
namespace {

bool finite(const ErrorPlotPoint& p) {
  return std::isfinite(p.time_s) && std::isfinite(p.error_x_m) && std::isfinite(p.error_y_m) &&
         std::isfinite(p.error_theta_rad) && std::isfinite(p.sigma_x_m) &&
         std::isfinite(p.sigma_y_m) && std::isfinite(p.sigma_theta_rad) &&
         std::isfinite(p.correlation_xy) && std::isfinite(p.dr_position_error_m) &&
         std::isfinite(p.nees);
}

struct SeriesSpec {
  const char* name;
  QColor colour;
  Qt::PenStyle style;
  double (*value)(const ErrorPlotPoint&);
};

const QColor kX(31, 119, 180);      // blue
const QColor kY(214, 39, 40);       // red
const QColor kTh(44, 160, 44);      // green
const QColor kDr(255, 127, 14);     // orange
const QColor kCorr(148, 103, 189);  // purple

}  // namespace

struct ErrorPlotPanel::Chart {
  QChart* chart = nullptr;
  QChartView* view = nullptr;
  QValueAxis* x_axis = nullptr;
  QValueAxis* y_axis = nullptr;
  std::vector<QLineSeries*> series;
  std::vector<SeriesSpec> specs;
  bool symmetric = true;  // y range symmetric about 0
};

ErrorPlotPanel::ErrorPlotPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  auto* header = new QHBoxLayout;
  title_ = new QLabel(tr("No estimator running"), this);
  QFont bold = title_->font();
  bold.setBold(true);
  title_->setFont(bold);
  stats_ = new QLabel(this);
  auto* csv = new QPushButton(tr("Export CSV…"), this);
  auto* png = new QPushButton(tr("Export PNG…"), this);
  csv->setObjectName(QStringLiteral("exportCsvButton"));
  png->setObjectName(QStringLiteral("exportPngButton"));
  header->addWidget(title_);
  header->addStretch(1);
  header->addWidget(csv);
  header->addWidget(png);
  layout->addLayout(header);
  layout->addWidget(stats_);
  tabs_ = new QTabWidget(this);
  layout->addWidget(tabs_, 1);

  auto make = [this](const QString& tab, const QString& y_title, std::vector<SeriesSpec> specs,
                     bool symmetric) {
    auto* c = new Chart;
    c->chart = new QChart;
    c->chart->setMargins(QMargins(2, 2, 2, 2));
    c->chart->legend()->setAlignment(Qt::AlignBottom);
    c->chart->setAnimationOptions(QChart::NoAnimation);
    c->x_axis = new QValueAxis;
    c->x_axis->setTitleText(tr("time [s]"));
    c->x_axis->setLabelFormat(QStringLiteral("%.0f"));
    c->y_axis = new QValueAxis;
    c->y_axis->setTitleText(y_title);
    c->y_axis->setLabelFormat(QStringLiteral("%.3g"));
    c->chart->addAxis(c->x_axis, Qt::AlignBottom);
    c->chart->addAxis(c->y_axis, Qt::AlignLeft);
    c->specs = std::move(specs);
    c->symmetric = symmetric;
    for (const SeriesSpec& s : c->specs) {
      auto* line = new QLineSeries;
      line->setName(tr(s.name));
      QPen pen(s.colour);
      pen.setWidthF(s.style == Qt::SolidLine ? 1.6 : 1.0);
      pen.setStyle(s.style);
      line->setPen(pen);
      c->chart->addSeries(line);
      line->attachAxis(c->x_axis);
      line->attachAxis(c->y_axis);
      c->series.push_back(line);
    }
    c->view = new QChartView(c->chart, tabs_);
    c->view->setRenderHint(QPainter::Antialiasing);
    tabs_->addTab(c->view, tab);
    charts_.push_back(c);
  };
  make(tr("Position error"), tr("error [m]"),
       {{"x error", kX, Qt::SolidLine, [](const ErrorPlotPoint& p) { return p.error_x_m; }},
        {"x ±3σ", kX, Qt::DashLine, [](const ErrorPlotPoint& p) { return 3.0 * p.sigma_x_m; }},
        {"", kX, Qt::DashLine, [](const ErrorPlotPoint& p) { return -3.0 * p.sigma_x_m; }},
        {"y error", kY, Qt::SolidLine, [](const ErrorPlotPoint& p) { return p.error_y_m; }},
        {"y ±3σ", kY, Qt::DashLine, [](const ErrorPlotPoint& p) { return 3.0 * p.sigma_y_m; }},
        {"", kY, Qt::DashLine, [](const ErrorPlotPoint& p) { return -3.0 * p.sigma_y_m; }}},
       true);
  make(tr("Heading error"), tr("error [deg]"),
       {{"heading error", kTh, Qt::SolidLine,
         [](const ErrorPlotPoint& p) { return radToDeg(p.error_theta_rad); }},
        {"±3σ", kTh, Qt::DashLine,
         [](const ErrorPlotPoint& p) { return 3.0 * radToDeg(p.sigma_theta_rad); }},
        {"", kTh, Qt::DashLine,
         [](const ErrorPlotPoint& p) { return -3.0 * radToDeg(p.sigma_theta_rad); }}},
       true);
  make(tr("Covariance"), tr("σ [m] / σθ [deg/10] / ρxy"),
       {{"σx [m]", kX, Qt::SolidLine, [](const ErrorPlotPoint& p) { return p.sigma_x_m; }},
        {"σy [m]", kY, Qt::SolidLine, [](const ErrorPlotPoint& p) { return p.sigma_y_m; }},
        {"σθ [deg/10]", kTh, Qt::SolidLine,
         [](const ErrorPlotPoint& p) { return 0.1 * radToDeg(p.sigma_theta_rad); }},
        {"ρxy", kCorr, Qt::DotLine, [](const ErrorPlotPoint& p) { return p.correlation_xy; }}},
       false);
  make(tr("vs dead reckoning"), tr("position error [m]"),
       {{"estimate |e|", kX, Qt::SolidLine,
         [](const ErrorPlotPoint& p) { return std::hypot(p.error_x_m, p.error_y_m); }},
        {"dead reckoning |e|", kDr, Qt::SolidLine,
         [](const ErrorPlotPoint& p) { return p.dr_position_error_m; }}},
       false);
  // Unnamed series are the lower bounds: hide their legend entries.
  for (Chart* c : charts_)
    for (std::size_t i = 0; i < c->series.size(); ++i)
      if (c->specs[i].name[0] == '\0')
        for (QLegendMarker* m : c->chart->legend()->markers(c->series[i]))
          m->setVisible(false);

  refresh_ = new QTimer(this);
  refresh_->setSingleShot(true);
  refresh_->setInterval(kRefreshInterval_ms);
  connect(refresh_, &QTimer::timeout, this, &ErrorPlotPanel::refreshNow);
  connect(csv, &QPushButton::clicked, this, &ErrorPlotPanel::onExportCsv);
  connect(png, &QPushButton::clicked, this, &ErrorPlotPanel::onExportPng);
  refreshNow();
}

ErrorPlotPanel::~ErrorPlotPanel() {
  for (Chart* c : charts_)
    delete c;  // the QChart belongs to its view, the view to the tab widget
}

void ErrorPlotPanel::setEstimatorName(const QString& name) {
  title_->setText(name);
}

bool ErrorPlotPanel::addPoint(const ErrorPlotPoint& point) {
  if (!finite(point))
    return false;
  if (!points_.empty()) {
    const double last = points_.back().time_s;
    if (point.time_s < last - 1.0)
      clear();
    else if (point.time_s < last + kMinSpacing_s)
      return false;
  }
  points_.push_back(point);
  if (points_.size() > kMaxPoints) {
    // Thin the older half: keeps the whole run visible at bounded cost.
    const std::size_t half = points_.size() / 2;
    std::vector<ErrorPlotPoint> thinned;
    thinned.reserve(points_.size());
    for (std::size_t i = 0; i < half; i += 2)
      thinned.push_back(points_[i]);
    thinned.insert(thinned.end(), points_.begin() + static_cast<std::ptrdiff_t>(half),
                   points_.end());
    points_ = std::move(thinned);
  }
  scheduleRefresh();
  return true;
}

void ErrorPlotPanel::clear() {
  points_.clear();
  refreshNow();
}

void ErrorPlotPanel::scheduleRefresh() {
  if (!refresh_->isActive())
    refresh_->start();
}

void ErrorPlotPanel::refreshNow() {
  refresh_->stop();
  const double t0 = points_.empty() ? 0.0 : points_.front().time_s;
  const double t1 = points_.empty() ? 1.0 : std::max(points_.back().time_s, t0 + 1.0);
  for (Chart* c : charts_) {
    double lo = 0.0, hi = 0.0;
    for (std::size_t i = 0; i < c->series.size(); ++i) {
      QList<QPointF> list;
      list.reserve(static_cast<qsizetype>(points_.size()));
      for (const ErrorPlotPoint& p : points_) {
        const double v = c->specs[i].value(p);
        list.append({p.time_s, v});
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      c->series[i]->replace(list);
    }
    if (c->symmetric) {
      const double m = std::max({std::abs(lo), std::abs(hi), 1e-3}) * 1.1;
      lo = -m;
      hi = m;
    } else {
      hi = std::max(hi * 1.1, lo + 1e-3);
      lo = std::min(lo * 1.1, 0.0);
    }
    c->x_axis->setRange(t0, t1);
    c->y_axis->setRange(lo, hi);
    // Round time ticks (0, 10, 20 s rather than 0, 17, 34 s) without widening the range.
    const double raw = (t1 - t0) / 6.0;
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw <= decade       ? decade
                        : raw <= 2 * decade ? 2 * decade
                        : raw <= 5 * decade ? 5 * decade
                                            : 10 * decade;
    c->x_axis->setTickType(QValueAxis::TicksDynamic);
    c->x_axis->setTickAnchor(0.0);
    c->x_axis->setTickInterval(step);
    c->y_axis->applyNiceNumbers();
  }
  if (points_.empty()) {
    stats_->setText(tr("Waiting for samples with ground truth…"));
    return;
  }
  const ErrorPlotPoint& p = points_.back();
  stats_->setText(
      tr("t = %1 s   |e| = %2 m (3σ %3 m)   heading %4° (3σ %5°)   dead reckoning |e| = %6 m%7")
          .arg(p.time_s, 0, 'f', 1)
          .arg(std::hypot(p.error_x_m, p.error_y_m), 0, 'f', 3)
          .arg(3.0 * std::hypot(p.sigma_x_m, p.sigma_y_m), 0, 'f', 3)
          .arg(radToDeg(p.error_theta_rad), 0, 'f', 2)
          .arg(3.0 * radToDeg(p.sigma_theta_rad), 0, 'f', 2)
          .arg(p.dr_position_error_m, 0, 'f', 3)
          .arg(p.nees >= 0.0 ? tr("   NEES %1").arg(p.nees, 0, 'f', 2) : QString()));
}

QString ErrorPlotPanel::exportCsv(const QString& path) const {
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate | QIODevice::Text))
    return tr("cannot write %1: %2").arg(path, file.errorString());
  QTextStream out(&file);
  out << "time_s,err_x_m,err_y_m,err_theta_deg,sigma_x_m,sigma_y_m,sigma_theta_deg,rho_xy,"
         "dr_err_pos_m,nees\n";
  for (const ErrorPlotPoint& p : points_)
    out << QString::asprintf("%.3f,%.5f,%.5f,%.4f,%.5f,%.5f,%.4f,%.4f,%.4f,%.4g\n", p.time_s,
                             p.error_x_m, p.error_y_m, radToDeg(p.error_theta_rad), p.sigma_x_m,
                             p.sigma_y_m, radToDeg(p.sigma_theta_rad), p.correlation_xy,
                             p.dr_position_error_m, p.nees);
  out.flush();
  file.close();
  if (file.error() != QFileDevice::NoError)
    return tr("cannot write %1: %2").arg(path, file.errorString());
  return {};
}

QString ErrorPlotPanel::exportPng(const QString& path, QSize size) const {
  const Chart* c = charts_[static_cast<std::size_t>(std::max(0, tabs_->currentIndex()))];
  const QSize s = size.isValid() && !size.isEmpty() ? size : c->view->size();
  if (s.isEmpty())
    return tr("cannot render an empty chart");
  QPixmap pixmap(s);
  pixmap.fill(Qt::white);
  {
    // Render the chart at the requested size without resizing the visible view.
    QPainter painter(&pixmap);
    painter.setRenderHint(QPainter::Antialiasing);
    const QSizeF old = c->chart->size();
    c->chart->resize(QSizeF(s));
    c->chart->scene()->render(&painter, QRectF(QPointF(0, 0), QSizeF(s)),
                              QRectF(c->chart->pos(), QSizeF(s)));
    c->chart->resize(old);
  }
  if (!pixmap.save(path, "PNG"))
    return tr("cannot write %1").arg(path);
  return {};
}

int ErrorPlotPanel::currentChart() const {
  return tabs_->currentIndex();
}

void ErrorPlotPanel::setCurrentChart(int index) {
  tabs_->setCurrentIndex(index);
}

void ErrorPlotPanel::onExportCsv() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export localization errors"),
                                                    QStringLiteral("localization_errors.csv"),
                                                    tr("CSV files (*.csv)"));
  if (path.isEmpty())
    return;
  const QString error = exportCsv(path);
  stats_->setText(error.isEmpty() ? tr("Wrote %1").arg(path) : error);
  emit exportRequested();
}

void ErrorPlotPanel::onExportPng() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export chart"), QStringLiteral("localization_errors.png"), tr("PNG (*.png)"));
  if (path.isEmpty())
    return;
  const QString error = exportPng(path);
  stats_->setText(error.isEmpty() ? tr("Wrote %1").arg(path) : error);
  emit exportRequested();
}

}  // namespace irgs::widgets
