#pragma once
// Writes a session recording (recording_format.hpp). Producers on any thread append rows to a
// queue (a copy and a lock, nothing else: the link tap runs on the io thread); one writer thread
// owns the SQLite connection and commits everything queued in one transaction every
// flush_period_s, so SIGKILL loses at most one period of data plus what was being written.
// Write failures (disk full, file removed) are reported in stats().last_error and the rows
// counted as dropped; recording never throws into the producers.
//
// Qt Sql needs a QCoreApplication (driver plugins); create one before open().

#include "app/recording/recording_format.hpp"
#include "comms/link/frame_tap.hpp"

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace irgs::recording {

struct RecorderConfig {
  double flush_period_s = 0.25;          // transaction period; (0, 1] (SIGKILL loses at most this)
  std::size_t max_queued_rows = 200000;  // beyond this rows are dropped (writer stalled)
};

struct RecorderStats {
  std::uint64_t frames = 0;  // rows committed, per table
  std::uint64_t frame_bytes = 0;
  std::uint64_t events = 0;
  std::uint64_t truth = 0;
  std::uint64_t commands = 0;
  std::uint64_t transactions = 0;
  std::uint64_t dropped_rows = 0;  // queue overflow or failed writes
  std::string last_error;          // empty while every write succeeded
};

class SessionRecorder {
 public:
  struct OpenResult {
    std::unique_ptr<SessionRecorder> recorder;  // null when error is set
    std::string error;
  };
  // Creates `path` (its directory must exist; an existing non-empty file is refused, never
  // overwritten) and writes `meta` plus format_version and created_utc. Throws
  // std::invalid_argument for a config out of range.
  static OpenResult create(const std::string& path, const std::map<std::string, std::string>& meta,
                           RecorderConfig config = {});
  // Commits what is queued and closes the file.
  ~SessionRecorder();
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  // ---- any thread, cheap ----
  void recordFrame(comms::TapDirection direction, std::chrono::steady_clock::time_point time,
                   std::span<const std::uint8_t> bytes);
  void recordEvent(std::string_view kind, std::string_view text);
  // Simulator ground truth (world frame). Non-finite values are ignored.
  void recordTruth(double x_m, double y_m, double theta_rad);
  void recordCommand(std::string_view text);
  void setMeta(std::string_view key, std::string_view value);
  // A tap for LinkConfig::tap. It may outlive the recorder (it does nothing afterwards).
  comms::FrameTap tap() const;

  // Seconds since the recording started (the `t` of rows recorded now).
  double now_s() const;
  // Blocks until every row queued before the call is committed (or failed).
  void flush();
  RecorderStats stats() const;
  const std::string& path() const { return path_; }

  struct Shared;  // queue + writer state (session_recorder.cpp)

 private:
  SessionRecorder(std::string path, std::shared_ptr<Shared> shared);
  std::string path_;
  std::shared_ptr<Shared> shared_;
};

}  // namespace irgs::recording
