#pragma once
// Where irgs keeps its settings, and the keys it uses. Normally the user's settings for
// organisation "IRGS", application "irgs"; an explicit INI file (--settings FILE or
// $IRGS_SETTINGS_FILE) isolates tests and demos from the user's own settings.

#include <QSettings>
#include <QString>
#include <memory>

namespace irgs::gui {

inline constexpr char kOrganisation[] = "IRGS";
inline constexpr char kApplication[] = "irgs";

// `file` from the command line wins over $IRGS_SETTINGS_FILE; both empty: the user's settings.
std::unique_ptr<QSettings> openSettings(const QString& file);

// Writes the settings out and makes their file readable by the user only (it holds the MAVLink
// signing key). Returns false when the file's permissions could not be set.
bool restrictSettingsToOwner(QSettings& settings);

namespace settings_key {
inline constexpr char kWindowGeometry[] = "window/geometry";
inline constexpr char kWindowState[] = "window/state";
inline constexpr char kMainSplitter[] = "window/mainSplitter";
inline constexpr char kSideSplitter[] = "window/sideSplitter";
inline constexpr char kRecentFiles[] = "files/recent";
inline constexpr char kLastMap[] = "files/lastMap";
inline constexpr char kLastDirectory[] = "files/lastDirectory";
inline constexpr char kLinearSpeed[] = "drive/linear_mps";
inline constexpr char kAngularSpeed[] = "drive/angular_radps";
inline constexpr char kFollowRobot[] = "view/followRobot";
inline constexpr char kLayerGroup[] = "view/layers";  // one bool per layer name
// MAVLink signing of robot links (the connection dialog): on/off and the key as 64 hex digits.
// The key lives only here, in the user's settings (a file readable by the user only).
inline constexpr char kLinkSigning[] = "link/signing";
inline constexpr char kLinkSigningKey[] = "link/signingKey";
}  // namespace settings_key

}  // namespace irgs::gui
