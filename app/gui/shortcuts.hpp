#pragma once
// The keyboard shortcuts, in one table for the menus' help dialog (and docs/gui.md mirrors it).

#include <QKeySequence>
#include <QString>
#include <vector>

namespace irgs::gui::shortcuts {

inline const QKeySequence kRunPause(Qt::Key_P);
inline const QKeySequence kStep(Qt::Key_N);
inline const QKeySequence kSpeed1(Qt::CTRL | Qt::Key_1);
inline const QKeySequence kSpeed2(Qt::CTRL | Qt::Key_2);
inline const QKeySequence kSpeed10(Qt::CTRL | Qt::Key_3);
inline const QKeySequence kSpeedMax(Qt::CTRL | Qt::Key_4);
inline const QKeySequence kResetRobot(Qt::CTRL | Qt::Key_R);
inline const QKeySequence kZoomToFit(Qt::CTRL | Qt::Key_0);
inline const QKeySequence kFollowRobot(Qt::CTRL | Qt::Key_L);
inline const QKeySequence kClearTrail(Qt::CTRL | Qt::SHIFT | Qt::Key_T);
inline const QKeySequence kResetGrid(Qt::CTRL | Qt::SHIFT | Qt::Key_G);
inline const QKeySequence kHelp(Qt::Key_F1);

struct Entry {
  QString keys;
  QString action;
};

// Every shortcut with what it does, grouped as in the menus, for the help dialog.
std::vector<Entry> table();

}  // namespace irgs::gui::shortcuts
