#pragma once
// The session recording file (docs/gui.md, "Recording and replay"): one SQLite database per
// session, WAL journal, written in batches (one transaction at least every flush period, 0.25 s
// by default) so a killed process loses at most the last batch. Times `t` are seconds on the
// recorder's steady clock since the recording started; bytes are the raw link bytes.
//
//   meta(key TEXT PRIMARY KEY, value TEXT)          format_version, created_utc, program, ...
//   frames(id, t REAL, dir INTEGER, bytes BLOB)     dir 0 = received chunk, 1 = sent frame
//   events(id, t REAL, kind TEXT, text TEXT)        console lines (kind info|warning|error|...)
//   truth(id, t REAL, x REAL, y REAL, theta REAL)   simulator ground truth, world frame, m / rad
//   commands(id, t REAL, text TEXT)                 user commands ("drive 0.200 0.000", ...)

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace irgs::recording {

inline constexpr int kFormatVersion = 1;
inline constexpr char kFileSuffix[] = ".irgsrec";

struct RecordedFrame {
  double t_s = 0.0;
  std::uint8_t dir = 0;  // comms::TapDirection
  std::vector<std::uint8_t> bytes;
};

struct RecordedEvent {
  double t_s = 0.0;
  std::string kind;
  std::string text;
};

struct RecordedTruth {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
};

struct RecordedCommand {
  double t_s = 0.0;
  std::string text;
};

// A whole recording in memory, rows ordered by time (ties in recording order).
struct Recording {
  std::map<std::string, std::string> meta;
  std::vector<RecordedFrame> frames;  // both directions
  std::vector<RecordedEvent> events;
  std::vector<RecordedTruth> truth;
  std::vector<RecordedCommand> commands;

  // Time of the last row of any table, s (0 for an empty recording).
  double duration_s() const;
  std::size_t receivedFrameCount() const;
};

}  // namespace irgs::recording
