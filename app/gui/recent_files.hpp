#pragma once
// The "Open Recent" list: most recent first, no duplicates, bounded, without missing files.

#include <QString>
#include <QStringList>

namespace irgs::gui {

inline constexpr int kMaxRecentFiles = 8;

// Puts `path` (made absolute) at the front, removes its older entry, keeps at most `max` entries.
QStringList addRecentFile(const QStringList& recent, const QString& path,
                          int max = kMaxRecentFiles);

// Removes entries whose file no longer exists, and duplicates, and trims to `max`.
QStringList pruneRecentFiles(const QStringList& recent, int max = kMaxRecentFiles);

}  // namespace irgs::gui
