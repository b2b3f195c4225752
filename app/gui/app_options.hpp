#pragma once
// The irgs command line, parsed into plain values. Parsing is separate from main() so it can be
// tested and so every bad argument produces one clear message instead of a half-started window.

#include <QSize>
#include <QString>
#include <QStringList>
#include <cstdint>
#include <optional>

namespace irgs::gui {

struct AppOptions {
  QString map_file;                 // empty: last map from the settings, else the bundled default
  QString robot_file;               // empty: the bundled thesis robot
  std::uint64_t seed = 1;           // simulator noise seed
  QString settings_file;            // empty: the user's normal settings (or $IRGS_SETTINGS_FILE)
  QString drive_script_file;        // drive commands replayed by simulated time
  QString screenshot_file;          // grab the window into this PNG, then exit 0
  double screenshot_after_s = 5.0;  // simulated seconds before the screenshot
  std::optional<double> quit_after_s;  // wall-clock seconds; a guard for demos and tests
  std::optional<QSize> window_size;    // overrides the saved geometry (screenshots)
  std::optional<double> sim_speed;     // initial speed factor, 0 = max
  QString connect_url;                 // start linked to this robot (serial://, tcp://, udp://)
  bool control_stdin = false;          // read commands from stdin (stdin_control.hpp)
  std::optional<double> status_interval_s;  // print status lines on stdout this often
  QString localize;  // start this estimator: ekf, dr or encoder-gyro (empty: off)
  // Session recording (app/recording): a new file per session under the recordings folder
  // unless --no-record; --record names the file.
  QString record_file;
  bool no_record = false;
  QString replay_file;                 // replay this recording as the robot link at start-up
  std::optional<double> replay_speed;  // x0.25 .. x16 (default 1)
  QString trajectory_out_file;         // at exit: every shown pose (t, x, y, theta) as CSV
  QString grid_out_file;               // at exit: the occupancy grid's log-odds as CSV
};

struct AppOptionsResult {
  std::optional<AppOptions> options;  // empty when parsing failed or help/version was asked
  QString message;                    // error text (exit 2) or help/version text (exit 0)
  int exit_code = 0;
};

// Parses the full argument list (arguments[0] is the program name).
AppOptionsResult parseAppOptions(const QStringList& arguments);

}  // namespace irgs::gui
