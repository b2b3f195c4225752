// Checks a screenshot of the irgs window taken after a short scripted drive:
//   screenshot_check PNG WIDTHxHEIGHT
// The map canvas is the left part of the window (the side column is MainWindow's 360 px). It must
// show many dark wall pixels, the robot's blue body, and light-blue free cells of the sonar grid.
// Prints what it counted; exit 0 when every check passes, 1 otherwise, 2 on bad arguments.

#include <QColor>
#include <QImage>
#include <QRect>
#include <QString>
#include <QTextStream>
#include <cstdlib>

#include "widgets/canvas/grid_image.hpp"

namespace {

// Pixels of the canvas taken as "wall coloured": all channels this dark or darker.
constexpr int kDarkMax = 90;
constexpr int kMinWallPixels = 1500;
// The robot body: kRobotFill (30, 136, 229) at alpha 215 over the light floor or the grid.
constexpr int kMinRobotPixels = 40;
constexpr int kMinFreePixels = 2000;
constexpr int kColourTolerance = 14;
constexpr int kSideColumn = 360 + 40;  // MainWindow::kSideColumnWidth and splitter slack
constexpr int kMenuAndStatus = 40;     // px excluded at the top and bottom

bool near(QRgb c, int r, int g, int b, int tolerance) {
  return std::abs(qRed(c) - r) <= tolerance && std::abs(qGreen(c) - g) <= tolerance &&
         std::abs(qBlue(c) - b) <= tolerance;
}

bool isRobotBody(QRgb c) {
  return qRed(c) >= 40 && qRed(c) <= 95 && qGreen(c) >= 128 && qGreen(c) <= 178 &&
         qBlue(c) >= 205 && qBlue(c) <= 248;
}

}  // namespace

int main(int argc, char** argv) {
  QTextStream out(stdout);
  if (argc != 3) {
    out << "usage: screenshot_check PNG WIDTHxHEIGHT\n";
    return 2;
  }
  const QStringList size = QString::fromLocal8Bit(argv[2]).split(QLatin1Char('x'));
  if (size.size() != 2 || size[0].toInt() <= 0 || size[1].toInt() <= 0) {
    out << "bad size " << argv[2] << "\n";
    return 2;
  }
  const int want_w = size[0].toInt(), want_h = size[1].toInt();
  const QImage image(QString::fromLocal8Bit(argv[1]));
  bool ok = true;
  if (image.isNull()) {
    out << "FAIL: cannot read " << argv[1] << "\n";
    return 1;
  }
  out << "screenshot " << image.width() << "x" << image.height() << "\n";
  if (image.width() != want_w || image.height() != want_h) {
    out << "FAIL: expected the window size " << want_w << "x" << want_h << "\n";
    ok = false;
  }

  const QRect canvas(0, kMenuAndStatus, image.width() - kSideColumn,
                     image.height() - 2 * kMenuAndStatus);
  const QColor free = irgs::widgets::kGridFreeColour;
  long dark = 0, robot = 0, grid_free = 0;
  for (int y = canvas.top(); y <= canvas.bottom(); ++y) {
    for (int x = canvas.left(); x <= canvas.right(); ++x) {
      const QRgb c = image.pixel(x, y);
      if (qRed(c) <= kDarkMax && qGreen(c) <= kDarkMax && qBlue(c) <= kDarkMax)
        ++dark;
      if (isRobotBody(c))
        ++robot;
      if (near(c, free.red(), free.green(), free.blue(), kColourTolerance))
        ++grid_free;
    }
  }
  out << "canvas " << canvas.width() << "x" << canvas.height() << ": dark (walls) " << dark
      << ", robot body " << robot << ", grid free " << grid_free << "\n";
  if (dark < kMinWallPixels) {
    out << "FAIL: fewer than " << kMinWallPixels << " dark wall pixels\n";
    ok = false;
  }
  if (robot < kMinRobotPixels) {
    out << "FAIL: fewer than " << kMinRobotPixels << " robot body pixels\n";
    ok = false;
  }
  if (grid_free < kMinFreePixels) {
    out << "FAIL: fewer than " << kMinFreePixels << " free grid pixels (sonar map empty?)\n";
    ok = false;
  }
  out << (ok ? "PASS\n" : "FAILED\n");
  return ok ? 0 : 1;
}
