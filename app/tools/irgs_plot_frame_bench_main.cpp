// irgs-plot-frame-bench: the frame time of the ground-station window with and without the plots
// dock, in one run (issue 6 acceptance: "plotting 20 fields at 50 Hz for 10 minutes keeps the
// GUI responsive"). Builds the real MainWindow offscreen on a bundled map with the simulated
// robot, feeds 20 fields at 50 Hz of simulated time into the window's plot hub and renders the
// whole window (QWidget::grab: every visible widget paints) every frame period:
//   1. "no plots": the plots dock hidden (the hub is still fed: the same work minus drawing);
//   2. "plots":    the dock shown with 4 panels x 5 fields = 20 traces, a 10-minute window
//                  (so at the end each trace draws 30 000 samples through the decimation).
// Prints the median / 95th percentile / max frame time per variant over the whole run and over
// its last minute. Usage:
//   QT_QPA_PLATFORM=offscreen irgs-plot-frame-bench [--minutes 10] [--frame-every 5]
// --frame-every N renders every Nth 50 ms frame (all frames are fed) to keep the run short.

#include <QApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QSettings>
#include <QTemporaryDir>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "app/gui/main_window.hpp"
#include "app/gui/plots_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plot_panel.hpp"
#include "widgets/plots/plots_dock.hpp"

namespace {

constexpr int kFields = 20;
constexpr double kRate_hz = 50.0;
constexpr double kFramePeriod_s = 0.05;  // the dock's refresh interval

struct Stats {
  double median_ms = 0.0;
  double p95_ms = 0.0;
  double max_ms = 0.0;
  std::size_t frames = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty())
    return s;
  std::sort(v.begin(), v.end());
  s.frames = v.size();
  s.median_ms = v[v.size() / 2];
  s.p95_ms = v[std::min(v.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(v.size())))];
  s.max_ms = v.back();
  return s;
}

QString fieldKey(int i) {
  return QStringLiteral("Bench/Group %1/field %2").arg(i / 5).arg(i, 2, 10, QLatin1Char('0'));
}

struct RunResult {
  Stats all;
  Stats last_minute;
};

RunResult run(irgs::gui::MainWindow& window, bool with_plots, double minutes, int frame_every) {
  irgs::gui::PlotsController& plots = window.plots();
  irgs::widgets::PlotDataHub& hub = plots.hub();
  hub.clearSamples();
  irgs::widgets::PlotsDock& dock = plots.plots();
  plots.dock().setVisible(with_plots);
  if (with_plots) {
    while (dock.panelCount() < 4)
      dock.addPanel();
    dock.setWindow_s(600.0);
    for (int i = 0; i < kFields; ++i) {
      dock.setCurrentPanel(&dock.panel(i / 5));
      dock.plotFields({fieldKey(i)});
    }
  }
  QApplication::processEvents();
  std::mt19937_64 rng(42);
  std::normal_distribution<double> noise(0.0, 0.05);
  const double duration_s = minutes * 60.0;
  const long samples = std::lround(duration_s * kRate_hz);
  std::vector<double> all;
  std::vector<double> last;
  long frame = 0;
  double next_frame_s = kFramePeriod_s;
  for (long n = 0; n < samples; ++n) {
    const double t = static_cast<double>(n) / kRate_hz;
    for (int i = 0; i < kFields; ++i)
      hub.record(fieldKey(i), QStringLiteral("m"), t, std::sin(0.1 * (i + 1) * t) + noise(rng));
    if (t + 1e-9 < next_frame_s)
      continue;
    next_frame_s += kFramePeriod_s;
    if (++frame % frame_every != 0)
      continue;
    QElapsedTimer clock;
    clock.start();
    dock.refreshNow();
    const QPixmap pixmap = window.grab();
    const double ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
    (void)pixmap;
    all.push_back(ms);
    if (t >= duration_s - 60.0)
      last.push_back(ms);
    QApplication::processEvents();
  }
  return {stats(all), stats(last)};
}

void print(const char* name, const RunResult& r) {
  std::printf(
      "%-9s all frames: n=%zu median %.2f ms  p95 %.2f ms  max %.2f ms | last minute: "
      "n=%zu median %.2f ms  p95 %.2f ms\n",
      name, r.all.frames, r.all.median_ms, r.all.p95_ms, r.all.max_ms, r.last_minute.frames,
      r.last_minute.median_ms, r.last_minute.p95_ms);
}

}  // namespace

int main(int argc, char** argv) {
  double minutes = 10.0;
  int frame_every = 5;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--minutes") == 0 && i + 1 < argc) {
      minutes = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--frame-every") == 0 && i + 1 < argc) {
      frame_every = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: irgs-plot-frame-bench [--minutes M] [--frame-every N]\n");
      return 2;
    }
  }
  if (!(minutes > 0.0)) {
    std::fprintf(stderr, "irgs-plot-frame-bench: --minutes must be positive\n");
    return 2;
  }
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
    qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  const std::string root = IRGS_SOURCE_DIR;
  irgs::RobotProfileResult profile =
      irgs::loadRobotProfileFile(root + "/resources/robots/thesis_robot.json");
  irgs::MapLoadResult map = irgs::loadMapFile(root + "/resources/maps/thesis_arena_250.json");
  if (!profile.profile || !map.map) {
    std::fprintf(stderr, "irgs-plot-frame-bench: bundled robot or map does not load\n");
    return 1;
  }
  irgs::gui::SessionController session(
      *profile.profile, [](const irgs::WorldMap& world, const irgs::RobotProfile& p) {
        return std::make_unique<irgs::SimulatedRobot>(world, p, irgs::SimConfig{});
      });
  session.loadWorld(*map.map, QStringLiteral("thesis_arena_250.json"));
  QTemporaryDir dir;
  QSettings settings(dir.filePath(QStringLiteral("bench.ini")), QSettings::IniFormat);
  irgs::gui::MainWindow window(session, settings);
  window.resize(1600, 1000);
  window.show();
  QApplication::processEvents();
  std::printf(
      "irgs-plot-frame-bench: %d fields at %.0f Hz for %.1f min of simulated time, window "
      "1600x1000, every %d-th 50 ms frame rendered\n",
      kFields, kRate_hz, minutes, frame_every);
  print("no plots", run(window, false, minutes, frame_every));
  print("plots", run(window, true, minutes, frame_every));
  return 0;
}
