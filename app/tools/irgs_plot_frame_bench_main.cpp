// irgs-plot-frame-bench: the frame time of the ground-station window with and without the plots
// dock, in one run (issue 6 acceptance: "plotting 20 fields at 50 Hz for 10 minutes keeps the
// GUI responsive"). Builds the real MainWindow offscreen on a bundled map with the simulated
// robot, feeds 20 fields at 50 Hz of simulated time into the window's plot hub and renders the
// whole window (QWidget::grab: every visible widget paints) every frame period:
//   1. "no plots": a window with the plots dock hidden (its hub is fed all the same);
//   2. "plots":    a second window with the dock shown, 4 panels x 5 fields = 20 traces, a
//                  10-minute window (at the end each trace draws 30 000 samples).
// Both windows get every sample and are rendered in turn at each measured frame (alternating
// which goes first), so the two variants see the same machine load.
// Prints the median / 95th percentile / max frame time per variant over the whole run and over
// its last minute. Usage:
//   QT_QPA_PLATFORM=offscreen irgs-plot-frame-bench [--minutes 10] [--frame-every 5]
//                                                   [--screenshot FILE.png]
// --frame-every N renders every Nth 50 ms frame (all frames are fed) to keep the run short;
// --screenshot saves the plots window at the end.

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
  s.p95_ms =
      v[std::min(v.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(v.size())))];
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

void preparePlots(irgs::gui::MainWindow& window, bool with_plots) {
  irgs::gui::PlotsController& plots = window.plots();
  plots.dock().setVisible(with_plots);
  if (!with_plots)
    return;
  irgs::widgets::PlotsDock& dock = plots.plots();
  while (dock.panelCount() < 4)
    dock.addPanel();
  dock.setWindow_s(600.0);
  // The fields exist once recorded: one sample first, then the traces.
  for (int i = 0; i < kFields; ++i)
    plots.hub().record(fieldKey(i), QStringLiteral("m"), 0.0, 0.0);
  for (int i = 0; i < kFields; ++i) {
    dock.setCurrentPanel(&dock.panel(i / 5));
    dock.plotFields({fieldKey(i)});
  }
  plots.hub().clearSamples();
}

// Both windows get the same samples; each measured frame renders both, in alternating order, so
// machine load (other builds) hits the two variants alike.
std::pair<RunResult, RunResult> run(irgs::gui::MainWindow& without, irgs::gui::MainWindow& with,
                                    double minutes, int frame_every) {
  preparePlots(without, false);
  preparePlots(with, true);
  QApplication::processEvents();
  std::mt19937_64 rng(42);
  std::normal_distribution<double> noise(0.0, 0.05);
  const double duration_s = minutes * 60.0;
  const long samples = std::lround(duration_s * kRate_hz);
  std::vector<double> all[2];
  std::vector<double> last[2];
  irgs::gui::MainWindow* windows[2] = {&without, &with};
  long frame = 0;
  double next_frame_s = kFramePeriod_s;
  for (long n = 0; n < samples; ++n) {
    const double t = static_cast<double>(n) / kRate_hz;
    for (int i = 0; i < kFields; ++i) {
      const double v = std::sin(0.1 * (i + 1) * t) + noise(rng);
      for (irgs::gui::MainWindow* w : windows)
        w->plots().hub().record(fieldKey(i), QStringLiteral("m"), t, v);
    }
    if (t + 1e-9 < next_frame_s)
      continue;
    next_frame_s += kFramePeriod_s;
    if (++frame % frame_every != 0)
      continue;
    for (int k = 0; k < 2; ++k) {
      // Alternate which variant renders first.
      const auto v = static_cast<std::size_t>((frame / frame_every + k) % 2);
      QElapsedTimer clock;
      clock.start();
      windows[v]->plots().plots().refreshNow();
      const QPixmap pixmap = windows[v]->grab();
      const double ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
      (void)pixmap;
      all[v].push_back(ms);
      if (t >= duration_s - 60.0)
        last[v].push_back(ms);
    }
    QApplication::processEvents();
  }
  return {{stats(all[0]), stats(last[0])}, {stats(all[1]), stats(last[1])}};
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
  QString screenshot;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--minutes") == 0 && i + 1 < argc) {
      minutes = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--screenshot") == 0 && i + 1 < argc) {
      screenshot = QString::fromLocal8Bit(argv[++i]);
    } else if (std::strcmp(argv[i], "--frame-every") == 0 && i + 1 < argc) {
      frame_every = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(
          stderr,
          "usage: irgs-plot-frame-bench [--minutes M] [--frame-every N] [--screenshot FILE.png]\n");
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
  auto factory = [](const irgs::WorldMap& world, const irgs::RobotProfile& p) {
    return std::make_unique<irgs::SimulatedRobot>(world, p, irgs::SimConfig{});
  };
  irgs::gui::SessionController session_a(*profile.profile, factory);
  irgs::gui::SessionController session_b(*profile.profile, factory);
  session_a.loadWorld(*map.map, QStringLiteral("thesis_arena_250.json"));
  session_b.loadWorld(*map.map, QStringLiteral("thesis_arena_250.json"));
  QTemporaryDir dir;
  QSettings settings_a(dir.filePath(QStringLiteral("a.ini")), QSettings::IniFormat);
  QSettings settings_b(dir.filePath(QStringLiteral("b.ini")), QSettings::IniFormat);
  irgs::gui::MainWindow without(session_a, settings_a);
  irgs::gui::MainWindow with(session_b, settings_b);
  for (irgs::gui::MainWindow* w : {&without, &with}) {
    w->resize(1600, 1000);
    w->show();
  }
  QApplication::processEvents();
  std::printf(
      "irgs-plot-frame-bench: %d fields at %.0f Hz for %.1f min of simulated time, window "
      "1600x1000, every %d-th 50 ms frame rendered (both windows, alternating)\n",
      kFields, kRate_hz, minutes, frame_every);
  const auto [a, b] = run(without, with, minutes, frame_every);
  print("no plots", a);
  print("plots", b);
  if (!screenshot.isEmpty() && !with.grab().save(screenshot, "PNG")) {
    std::fprintf(stderr, "irgs-plot-frame-bench: cannot write %s\n", qPrintable(screenshot));
    return 1;
  }
  return 0;
}
