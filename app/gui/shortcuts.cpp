#include "app/gui/shortcuts.hpp"

#include <QCoreApplication>

namespace irgs::gui::shortcuts {
namespace {

QString text(const QKeySequence& keys) {
  return keys.toString(QKeySequence::NativeText);
}
QString tr(const char* source) {
  return QCoreApplication::translate("Shortcuts", source);
}

}  // namespace

std::vector<Entry> table() {
  return {
      {tr("↑ / W"), tr("Drive forward (hold)")},
      {tr("↓ / S"), tr("Drive backward (hold)")},
      {tr("← / A"), tr("Turn left (hold; with forward: arc)")},
      {tr("→ / D"), tr("Turn right (hold; with forward: arc)")},
      {tr("Space"), tr("Stop the robot")},
      {text(kRunPause), tr("Run / pause the simulation")},
      {text(kStep), tr("Single simulation step (pauses)")},
      {text(kSpeed1) + QStringLiteral(" … ") + text(kSpeedMax),
       tr("Simulation speed 1×, 2×, 10×, max")},
      {text(kResetRobot), tr("Reset the robot to the map's start pose")},
      {text(QKeySequence(QKeySequence::Open)), tr("Open a map")},
      {text(QKeySequence(QKeySequence::Save)), tr("Save the map")},
      {text(kZoomToFit), tr("Zoom to fit")},
      {text(kFollowRobot), tr("Follow the robot")},
      {text(kClearTrail), tr("Clear the trail")},
      {text(kResetGrid), tr("Reset the occupancy grid")},
      {tr("Mouse drag / wheel"), tr("Pan / zoom the map")},
      {text(kHelp), tr("This list")},
      {text(QKeySequence(QKeySequence::Quit)), tr("Quit")},
  };
}

}  // namespace irgs::gui::shortcuts
