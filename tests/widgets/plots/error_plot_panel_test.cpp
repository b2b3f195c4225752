// The localization plots and the estimator overlay of the map canvas, offscreen.

#include "widgets/plots/error_plot_panel.hpp"

#include <gtest/gtest.h>

#include <QDir>
#include <QFile>
#include <QImage>
#include <QTemporaryDir>
#include <cmath>

#include "widgets/canvas/estimator_overlay.hpp"
#include "widgets/canvas/map_canvas.hpp"

namespace irgs::widgets {
namespace {

ErrorPlotPoint pointAt(double t) {
  ErrorPlotPoint p;
  p.time_s = t;
  p.error_x_m = 0.01 * std::sin(t);
  p.error_y_m = -0.02;
  p.error_theta_rad = degToRad(0.5);
  p.sigma_x_m = 0.02 + 0.001 * t;
  p.sigma_y_m = 0.01;
  p.sigma_theta_rad = degToRad(1.0);
  p.correlation_xy = 0.3;
  p.dr_position_error_m = 0.05 * t;
  p.nees = 1.5;
  return p;
}

TEST(ErrorPlotPanel, KeepsFinitePointsInTimeOrderAndThinsDenseFeeds) {
  ErrorPlotPanel panel;
  EXPECT_TRUE(panel.addPoint(pointAt(0.0)));
  EXPECT_FALSE(panel.addPoint(pointAt(0.01)));  // closer than kMinSpacing_s
  EXPECT_TRUE(panel.addPoint(pointAt(0.1)));
  ErrorPlotPoint bad = pointAt(0.5);
  bad.sigma_x_m = std::nan("");
  EXPECT_FALSE(panel.addPoint(bad));
  ErrorPlotPoint inf = pointAt(0.6);
  inf.error_theta_rad = INFINITY;
  EXPECT_FALSE(panel.addPoint(inf));
  EXPECT_EQ(panel.points().size(), 2u);
  // A clock far behind the last point is a new run: the plots restart.
  EXPECT_TRUE(panel.addPoint(pointAt(-5.0)));
  EXPECT_EQ(panel.points().size(), 1u);
}

TEST(ErrorPlotPanel, StaysBoundedOverALongRunAndKeepsItsEnds) {
  ErrorPlotPanel panel;
  for (int i = 0; i < 3 * static_cast<int>(ErrorPlotPanel::kMaxPoints); ++i)
    panel.addPoint(pointAt(0.1 * i));
  EXPECT_LE(panel.points().size(), ErrorPlotPanel::kMaxPoints);
  EXPECT_DOUBLE_EQ(panel.points().front().time_s, 0.0);
  EXPECT_NEAR(panel.points().back().time_s, 0.1 * (3 * ErrorPlotPanel::kMaxPoints - 1), 1e-9);
}

TEST(ErrorPlotPanel, ExportsCsvInDegreesAndAPngOfTheChart) {
  ErrorPlotPanel panel;
  panel.resize(700, 400);
  for (int i = 0; i < 50; ++i)
    panel.addPoint(pointAt(0.2 * i));
  panel.refreshNow();
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const QString csv = dir.filePath(QStringLiteral("errors.csv"));
  EXPECT_TRUE(panel.exportCsv(csv).isEmpty());
  QFile file(csv);
  ASSERT_TRUE(file.open(QIODevice::ReadOnly | QIODevice::Text));
  const QStringList lines = QString::fromUtf8(file.readAll()).split('\n', Qt::SkipEmptyParts);
  ASSERT_EQ(lines.size(), 51);
  EXPECT_TRUE(lines[0].startsWith(QStringLiteral("time_s,err_x_m,err_y_m,err_theta_deg")));
  const QStringList first = lines[1].split(',');
  EXPECT_NEAR(first[3].toDouble(), 0.5, 1e-3);  // heading error written in degrees
  EXPECT_NEAR(first[6].toDouble(), 1.0, 1e-3);

  const QString png = dir.filePath(QStringLiteral("errors.png"));
  panel.setCurrentChart(1);
  EXPECT_TRUE(panel.exportPng(png, QSize(640, 360)).isEmpty());
  const QImage image(png);
  ASSERT_FALSE(image.isNull());
  EXPECT_EQ(image.size(), QSize(640, 360));
  // Something besides the white background was drawn (axes, series).
  int dark = 0;
  for (int y = 0; y < image.height(); y += 2)
    for (int x = 0; x < image.width(); x += 2)
      if (qGray(image.pixel(x, y)) < 128)
        ++dark;
  EXPECT_GT(dark, 200);
  EXPECT_FALSE(panel.exportCsv(QStringLiteral("/nonexistent-dir/x.csv")).isEmpty());
}

TEST(EstimatorOverlay, TheTwoSigmaEllipseFollowsTheCovarianceEigenvectors) {
  Eigen::Matrix2d p;
  p << 0.04, 0.0, 0.0, 0.01;  // sigma 0.2 m along x, 0.1 m along y
  const auto e = sigmaEllipse(p, 2.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->major_m, 0.4, 1e-12);
  EXPECT_NEAR(e->minor_m, 0.2, 1e-12);
  EXPECT_NEAR(std::abs(std::sin(e->angle_rad)), 0.0, 1e-12);
  // Rotated by 45 degrees.
  const double c = std::sqrt(0.5);
  Eigen::Matrix2d r;
  r << c, -c, c, c;
  const auto rotated = sigmaEllipse(r * p * r.transpose(), 1.0);
  ASSERT_TRUE(rotated.has_value());
  EXPECT_NEAR(rotated->major_m, 0.2, 1e-12);
  EXPECT_NEAR(std::abs(std::tan(rotated->angle_rad)), 1.0, 1e-9);
  Eigen::Matrix2d indefinite;
  indefinite << 0.01, 0.0, 0.0, -0.01;
  EXPECT_FALSE(sigmaEllipse(indefinite, 2.0).has_value());
  EXPECT_FALSE(sigmaEllipse(Eigen::Matrix2d::Constant(std::nan("")), 2.0).has_value());
}

TEST(EstimatorOverlay, TheCanvasDrawsTheEstimateEllipseAndTheMatchedWall) {
  MapCanvas canvas;
  canvas.resize(400, 300);
  WorldMap map;
  map.walls.push_back({"w", {{-2.0, -1.0}, {2.0, -1.0}}, false, {}});
  canvas.setWorldMap(map);
  canvas.setView({0.0, 0.0}, 50.0);
  const QImage before = canvas.grab().toImage();
  EstimatorOverlay overlay;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.25 * 0.25, 0.1 * 0.1, degToRad(10.0) * degToRad(10.0);
  overlay.poses.push_back({QStringLiteral("EKF"), QColor(31, 119, 180), {0.0, 0.0, 0.0}, cov});
  MatchedFeatureMarker m;
  m.wall = Segment{{-2.0, -1.0}, {2.0, -1.0}};
  m.sensor = {0.0, -0.2};
  overlay.matches.push_back(m);
  // A non-finite pose is skipped, not drawn at a crazy place or crashing.
  overlay.poses.push_back({QStringLiteral("bad"), Qt::red, {std::nan(""), 0.0, 0.0}, cov});
  canvas.setEstimatorOverlay(overlay);
  const QImage after = canvas.grab().toImage();
  // The ellipse edge: 2 sigma = 0.5 m along x -> 25 px right of the centre (200, 150).
  const QColor edge = after.pixelColor(200 + 25, 150);
  EXPECT_GT(edge.blue(), edge.red() + 40) << "ellipse edge not drawn";
  // The matched wall at y = -1 m -> 50 px below the centre, highlighted in teal.
  const QColor wall = after.pixelColor(120, 200);
  EXPECT_GT(wall.green(), wall.red() + 60);
  EXPECT_NE(before.pixelColor(120, 200), wall);
  EXPECT_FALSE(canvas.estimatorOverlay().empty());
  canvas.setEstimatorOverlay({});
  EXPECT_TRUE(canvas.estimatorOverlay().empty());
}

}  // namespace
}  // namespace irgs::widgets
