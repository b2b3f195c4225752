#pragma once
// A session summary (issue 6, item 8): how long, how far, how good the link was and what
// happened, as Markdown or HTML. Built from a recording file (`irgs-summary`, File > Export in a
// replay) or from the live session (the GUI fills the same struct).
//
// From a recording: duration is the last row's time; distance is the path length of the
// robot's own odometry decoded from the received MAVLink frames (one pose message type, the
// first seen of LOCAL_POSITION_NED, IRGS_POSE_2D, ODOMETRY, so no pose is counted twice), or of
// the simulator truth rows when there are no frames; link quality is what a fresh MAVLink
// decoder makes of the received bytes (frames, CRC errors, sequence gaps) plus the recorded
// link events; events are the recorded console lines.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/recording/recording_format.hpp"

namespace irgs::recording {

struct SummaryLink {
  std::uint64_t frames_received = 0;
  std::uint64_t frames_sent = 0;
  std::uint64_t bytes_received = 0;
  std::uint64_t crc_errors = 0;
  std::uint64_t sequence_gaps = 0;
  std::uint64_t other_errors = 0;  // bad length, unknown id, garbage bytes counted as frames
  std::uint64_t link_losses = 0;
  double loss_percent = 0.0;                      // gaps / (frames + gaps)
  std::map<std::string, std::uint64_t> messages;  // received, by MAVLink name
};

struct SummaryEvent {
  double t_s = 0.0;
  std::string kind;  // info, warning, error, link, sensor ...
  std::string text;
};

struct SessionSummary {
  std::string title = "IRGS session summary";
  std::string source;                       // the recording file or "live session"
  std::map<std::string, std::string> meta;  // recording meta (program, created_utc ...)
  double duration_s = 0.0;
  double distance_m = 0.0;
  std::string distance_from;        // "odometry (LOCAL_POSITION_NED)", "simulator truth", ...
  std::optional<SummaryLink> link;  // none for a simulator session
  std::size_t commands = 0;
  std::map<std::string, std::size_t> event_counts;  // by kind
  std::vector<SummaryEvent> events;  // the notable ones (not info/sensor), in time order
};

// Events listed in full in the documents; the rest are counted.
inline constexpr std::size_t kMaxListedEvents = 200;

SessionSummary summarizeRecording(const Recording& recording, const std::string& source);

std::string summaryMarkdown(const SessionSummary& summary);
std::string summaryHtml(const SessionSummary& summary);
// Markdown for ".md"/".markdown", HTML for ".html"/".htm"; returns why not, or empty.
std::string writeSummary(const SessionSummary& summary, const std::string& path);

}  // namespace irgs::recording
