// The plots dock offscreen: fields from telemetry in the browser tree, drag and drop onto a
// panel, double-click to the current panel, scaling, min/max, pause, zoom, CSV and PNG export.

#include "widgets/plots/plots_dock.hpp"

#include <gtest/gtest.h>

#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QImage>
#include <QMimeData>
#include <QTemporaryDir>
#include <QTest>
#include <QTextStream>
#include <cmath>
#include <numbers>

#include "widgets/plots/field_browser.hpp"
#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plot_panel.hpp"
#include "widgets/plots/telemetry_plot_fields.hpp"

namespace irgs::widgets {
namespace {

TelemetrySample sampleAt(double t) {
  TelemetrySample s;
  s.time_s = t;
  s.odometry_pose = {0.1 * t, -0.2, 0.5 * std::sin(t)};
  s.true_pose = Pose2{0.1 * t, -0.2, 0.0};
  s.measured_velocity = {0.1, 0.0};
  s.left_ticks = static_cast<std::int64_t>(100 * t);
  s.right_ticks = static_cast<std::int64_t>(101 * t);
  s.sonar = {{3, 1.25, true}, {4, 0.0, false}};
  s.gyro = GyroReading{0.01, 24.0, false};
  return s;
}

void feed(PlotDataHub& hub, double until_s, double step_s = 0.02) {
  const auto n = static_cast<int>(std::lround(until_s / step_s));
  for (int i = 0; i <= n; ++i)
    hub.record(i * step_s, telemetryPlotFields(sampleAt(i * step_s)));
}

// What a drag from the browser would carry, dropped on `target`.
bool dropKeys(QWidget& target, const QMimeData& mime) {
  const QPoint at(target.width() / 2, target.height() / 2);
  QDragEnterEvent enter(at, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QCoreApplication::sendEvent(&target, &enter);
  if (!enter.isAccepted())
    return false;
  QDropEvent drop(QPointF(at), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QCoreApplication::sendEvent(&target, &drop);
  return drop.isAccepted();
}

TEST(TelemetryPlotFields, ListsEveryNumericFieldOfASample) {
  const auto fields = telemetryPlotFields(sampleAt(2.0));
  QStringList keys;
  for (const auto& f : fields)
    keys << f.key;
  EXPECT_TRUE(keys.contains(QStringLiteral("Telemetry/Odometry pose/theta")));
  EXPECT_TRUE(keys.contains(QStringLiteral("Telemetry/True pose (simulator)/x")));
  EXPECT_TRUE(keys.contains(QStringLiteral("Telemetry/Sonar/range 03")));
  EXPECT_FALSE(keys.contains(QStringLiteral("Telemetry/Sonar/range 04")));  // no echo
  EXPECT_TRUE(keys.contains(QStringLiteral("Telemetry/Gyro/temperature")));
  EXPECT_TRUE(keys.contains(QStringLiteral("Telemetry/Encoders/right")));
}

TEST(PlotsDock, BrowserShowsATreeBySourceAndDragsTheSelectedKeys) {
  PlotDataHub hub;
  PlotsDock dock(hub);
  feed(hub, 1.0);
  FieldBrowser& browser = dock.browser();
  ASSERT_EQ(browser.topLevelItemCount(), 1);
  EXPECT_EQ(browser.topLevelItem(0)->text(0), QStringLiteral("Telemetry"));
  QTreeWidgetItem* theta = browser.itemFor(QStringLiteral("Telemetry/Odometry pose/theta"));
  ASSERT_NE(theta, nullptr);
  EXPECT_EQ(theta->text(1), QStringLiteral("rad"));
  EXPECT_EQ(theta->parent()->text(0), QStringLiteral("Odometry pose"));
  QTreeWidgetItem* x = browser.itemFor(QStringLiteral("Telemetry/Odometry pose/x"));
  theta->setSelected(true);
  x->setSelected(true);
  EXPECT_EQ(browser.selectedKeys().size(), 2);

  // The panel accepts exactly what the browser puts on a drag.
  std::unique_ptr<QMimeData> mime(browser.mimeData(browser.selectedItems()));
  ASSERT_NE(mime, nullptr);
  dock.resize(900, 500);
  dock.show();
  PlotPanel& second = dock.panel(1);
  EXPECT_TRUE(dropKeys(second, *mime));
  ASSERT_EQ(second.traces().size(), 2u);
  EXPECT_EQ(dock.currentPanel(), &second);  // a drop makes the panel current
  EXPECT_TRUE(dock.panel(0).traces().empty());

  // Something else dragged in is refused.
  QMimeData text;
  text.setText(QStringLiteral("Telemetry/Odometry pose/y"));
  EXPECT_FALSE(dropKeys(dock.panel(0), text));
  EXPECT_TRUE(dock.panel(0).traces().empty());

  // The filter hides what does not match.
  browser.setFilter(QStringLiteral("gyro"));
  EXPECT_TRUE(theta->isHidden());
  EXPECT_FALSE(browser.itemFor(QStringLiteral("Telemetry/Gyro/rate"))->isHidden());
  browser.setFilter({});
  EXPECT_FALSE(theta->isHidden());
}

TEST(PlotsDock, BrowserOrdersNumbersByValueAndShowsThePathOnHover) {
  PlotDataHub hub;
  PlotsDock dock(hub);
  for (const char* key : {"MAVLink/IRGS_SONAR_SCAN/range[10]", "MAVLink/IRGS_SONAR_SCAN/range[2]",
                          "MAVLink/IRGS_SONAR_SCAN/count", "MAVLink/DISTANCE_SENSOR/id 10/x",
                          "MAVLink/DISTANCE_SENSOR/id 9/x"})
    hub.record(QString::fromLatin1(key), QStringLiteral("mm"), 1.0, 1.0);
  FieldBrowser& browser = dock.browser();
  QTreeWidgetItem* scan =
      browser.itemFor(QStringLiteral("MAVLink/IRGS_SONAR_SCAN/count"))->parent();
  ASSERT_EQ(scan->childCount(), 3);
  EXPECT_EQ(scan->child(0)->text(0), QStringLiteral("count"));
  EXPECT_EQ(scan->child(1)->text(0), QStringLiteral("range[2]"));
  EXPECT_EQ(scan->child(2)->text(0), QStringLiteral("range[10]"));
  QTreeWidgetItem* sonars =
      browser.itemFor(QStringLiteral("MAVLink/DISTANCE_SENSOR/id 9/x"))->parent()->parent();
  EXPECT_EQ(sonars->child(0)->text(0), QStringLiteral("id 9"));
  EXPECT_EQ(sonars->child(1)->text(0), QStringLiteral("id 10"));
  EXPECT_EQ(sonars->child(1)->toolTip(0), QStringLiteral("MAVLink/DISTANCE_SENSOR/id 10"));
  // Messages sort before "range" under MAVLink as plain text does.
  EXPECT_EQ(browser.topLevelItem(0)->child(0)->text(0), QStringLiteral("DISTANCE_SENSOR"));
}

TEST(PlotsDock, DoubleClickPlotsInTheCurrentPanel) {
  PlotDataHub hub;
  PlotsDock dock(hub);
  dock.resize(900, 500);
  dock.show();
  feed(hub, 1.0);
  dock.setCurrentPanel(&dock.panel(0));
  FieldBrowser& browser = dock.browser();
  QTreeWidgetItem* item = browser.itemFor(QStringLiteral("Telemetry/Velocity/linear"));
  ASSERT_NE(item, nullptr);
  item->parent()->setExpanded(true);
  browser.scrollToItem(item);
  browser.doItemsLayout();
  const QRect r = browser.visualItemRect(item);
  ASSERT_FALSE(r.isEmpty());
  // A real double-click: press, release, then the double-click event (with its press).
  QTest::mouseClick(browser.viewport(), Qt::LeftButton, Qt::NoModifier, r.center());
  QTest::mouseDClick(browser.viewport(), Qt::LeftButton, Qt::NoModifier, r.center());
  ASSERT_EQ(dock.panel(0).traces().size(), 1u);
  EXPECT_EQ(dock.panel(0).traces()[0].key, QStringLiteral("Telemetry/Velocity/linear"));
  // Again: not twice.
  EXPECT_FALSE(dock.panel(0).addField(QStringLiteral("Telemetry/Velocity/linear")));
  EXPECT_FALSE(dock.panel(0).addField(QStringLiteral("No/such/field")));
}

TEST(PlotPanel, ScalesAnglesToDegreesAndReportsTheVisibleMinMax) {
  PlotDataHub hub;
  PlotPanel panel(hub);
  panel.resize(600, 300);
  feed(hub, 60.0);
  ASSERT_TRUE(panel.addField(QStringLiteral("Telemetry/Odometry pose/theta")));
  ASSERT_TRUE(panel.addField(QStringLiteral("Telemetry/Odometry pose/x")));
  EXPECT_EQ(panel.traces()[0].display_unit, QStringLiteral("deg"));
  panel.setWindow_s(10.0);
  const auto [t0, t1] = panel.visibleTime();
  EXPECT_NEAR(t1, 60.0, 1e-6);
  EXPECT_NEAR(t0, 50.0, 1e-6);
  const auto x = panel.visibleRange(QStringLiteral("Telemetry/Odometry pose/x"));
  ASSERT_TRUE(x.has_value());
  EXPECT_NEAR(x->min, 5.0, 0.0021);  // the first sample at or after t = 50 s
  EXPECT_NEAR(x->max, 6.0, 1e-9);
  const auto theta = panel.visibleRange(QStringLiteral("Telemetry/Odometry pose/theta"));
  ASSERT_TRUE(theta.has_value());
  EXPECT_NEAR(theta->max, 0.5 * 180.0 / std::numbers::pi, 0.01);
  // A user scale: x in centimetres.
  ASSERT_TRUE(panel.setTraceScale(QStringLiteral("Telemetry/Odometry pose/x"), 100.0,
                                  QStringLiteral("cm")));
  EXPECT_NEAR(panel.visibleRange(QStringLiteral("Telemetry/Odometry pose/x"))->max, 600.0, 0.1);
  EXPECT_FALSE(panel.setTraceScale(QStringLiteral("Telemetry/Odometry pose/x"), 0.0, {}));
  // The fitted y axis holds every visible value.
  const PlotRange y = panel.visibleY();
  EXPECT_LE(y.min, -28.0);
  EXPECT_GE(y.max, 600.0);
}

TEST(PlotPanel, PauseFreezesTheWindowAndTheWheelZooms) {
  PlotDataHub hub;
  PlotPanel panel(hub);
  panel.resize(600, 300);
  panel.show();
  feed(hub, 20.0);
  panel.addField(QStringLiteral("Telemetry/Odometry pose/x"));
  panel.setPaused(true);
  const auto frozen = panel.visibleTime();
  for (double t = 20.02; t < 30.0; t += 0.02)
    hub.record(t, telemetryPlotFields(sampleAt(t)));
  EXPECT_EQ(panel.visibleTime(), frozen);
  const double before = panel.window_s();
  QWheelEvent wheel(QPointF(300, 150), panel.mapToGlobal(QPointF(300, 150)), QPoint(),
                    QPoint(0, 120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
  QCoreApplication::sendEvent(&panel, &wheel);
  EXPECT_LT(panel.window_s(), before);  // zoomed in
  QTest::mouseDClick(&panel, Qt::LeftButton);
  EXPECT_FALSE(panel.paused());
  EXPECT_NEAR(panel.visibleTime().second, hub.latestTime_s(), 1e-9);
}

TEST(PlotPanel, ExportsTheVisibleWindowAsCsvAndPng) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  PlotDataHub hub;
  PlotPanel panel(hub);
  panel.resize(640, 320);
  feed(hub, 10.0, 0.5);
  panel.addField(QStringLiteral("Telemetry/Odometry pose/x"));
  panel.addField(QStringLiteral("Telemetry/Sonar/range 03"));
  panel.setWindow_s(2.0);  // t in [8, 10]: 5 samples
  const QString csv = dir.filePath(QStringLiteral("plot.csv"));
  ASSERT_EQ(panel.exportCsv(csv), QString());
  QFile file(csv);
  ASSERT_TRUE(file.open(QIODevice::ReadOnly | QIODevice::Text));
  const QStringList lines = QString::fromUtf8(file.readAll()).split('\n', Qt::SkipEmptyParts);
  ASSERT_EQ(lines.size(), 6);
  EXPECT_EQ(
      lines[0],
      QStringLiteral("time_s,\"Telemetry/Odometry pose/x [m]\",\"Telemetry/Sonar/range 03 [m]\""));
  EXPECT_EQ(lines[1], QStringLiteral("8,0.8,1.25"));
  EXPECT_EQ(lines[5], QStringLiteral("10,1,1.25"));

  const QString png = dir.filePath(QStringLiteral("plot.png"));
  ASSERT_EQ(panel.exportPng(png, QSize(500, 250)), QString());
  QImage image(png);
  ASSERT_EQ(image.size(), QSize(500, 250));
  // The first trace's colour is drawn somewhere in the plot.
  const QColor trace = panel.traces()[0].colour;
  int hits = 0;
  for (int yy = 40; yy < image.height(); ++yy)
    for (int xx = 60; xx < image.width(); ++xx)
      hits += image.pixelColor(xx, yy) == trace ? 1 : 0;
  EXPECT_GT(hits, 50);
  EXPECT_NE(panel.exportCsv(dir.filePath(QStringLiteral("no/such/dir/x.csv"))), QString());
}

}  // namespace
}  // namespace irgs::widgets
