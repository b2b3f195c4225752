#include "app/recording/session_summary.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/message_info.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::recording {
namespace {

namespace mav = comms::mavlink;

bool notable(const std::string& kind) {
  return kind != "info" && kind != "sensor";
}

std::string fixed(double v, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

std::string duration(double s) {
  const auto total = static_cast<long>(std::floor(s));
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld (%.1f s)", total / 3600, (total / 60) % 60,
                total % 60, s);
  return buffer;
}

std::string htmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Markdown table cells: a pipe would end the cell, a newline the row.
std::string mdCell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out;
}

// Rows shown by both formats: (label, value).
std::vector<std::pair<std::string, std::string>> overview(const SessionSummary& s) {
  std::vector<std::pair<std::string, std::string>> rows;
  rows.emplace_back("Source", s.source);
  for (const auto& [key, value] : s.meta)
    rows.emplace_back(key, value);
  rows.emplace_back("Duration", duration(s.duration_s));
  rows.emplace_back("Distance", fixed(s.distance_m, 2) + " m" +
                                    (s.distance_from.empty() ? "" : " (" + s.distance_from + ")"));
  rows.emplace_back("User commands", std::to_string(s.commands));
  std::string counts;
  for (const auto& [kind, n] : s.event_counts)
    counts += (counts.empty() ? "" : ", ") + kind + " " + std::to_string(n);
  rows.emplace_back("Console events", counts.empty() ? "none" : counts);
  return rows;
}

std::vector<std::pair<std::string, std::string>> linkRows(const SummaryLink& l) {
  return {{"Frames received", std::to_string(l.frames_received)},
          {"Frames sent", std::to_string(l.frames_sent)},
          {"Bytes received", std::to_string(l.bytes_received)},
          {"CRC errors", std::to_string(l.crc_errors)},
          {"Sequence gaps (frames lost)", std::to_string(l.sequence_gaps)},
          {"Other decode errors", std::to_string(l.other_errors)},
          {"Loss", fixed(l.loss_percent, 2) + " %"},
          {"Link losses", std::to_string(l.link_losses)}};
}

}  // namespace

SessionSummary summarizeRecording(const Recording& recording, const std::string& source) {
  SessionSummary s;
  s.source = source;
  s.meta = recording.meta;
  s.duration_s = recording.duration_s();
  s.commands = recording.commands.size();
  for (const RecordedEvent& e : recording.events) {
    ++s.event_counts[e.kind];
    if (notable(e.kind))
      s.events.push_back({e.t_s, e.kind, e.text});
  }

  if (!recording.frames.empty()) {
    SummaryLink link;
    mav::FrameDecoder decoder;
    std::vector<mav::Frame> frames;
    std::optional<std::uint32_t> pose_id;  // the pose message type the distance follows
    std::optional<std::pair<double, double>> last;
    for (const RecordedFrame& f : recording.frames) {
      if (f.dir != 0) {
        ++link.frames_sent;
        continue;
      }
      link.bytes_received += f.bytes.size();
      frames.clear();
      decoder.feed(std::span<const std::uint8_t>(f.bytes.data(), f.bytes.size()), frames);
      for (const mav::Frame& frame : frames) {
        const auto info = mav::findMessageInfo(frame.message_id);
        ++link.messages[info ? std::string(info->name) : "#" + std::to_string(frame.message_id)];
        std::optional<std::pair<double, double>> xy;
        if (const auto p = frame.as<mav::LocalPositionNed>())
          xy = std::pair<double, double>(p->x, p->y);
        else if (const auto q = frame.as<mav::IrgsPose2d>())
          xy = std::pair<double, double>(q->x, q->y);
        else if (const auto o = frame.as<mav::Odometry>())
          xy = std::pair<double, double>(o->x, o->y);
        if (!xy)
          continue;
        if (!pose_id)
          pose_id = frame.message_id;
        if (frame.message_id != *pose_id)
          continue;
        if (last) {
          const double step = std::hypot(xy->first - last->first, xy->second - last->second);
          // A jump beyond 1 m between two 20 Hz poses is a robot restart, not travel.
          if (std::isfinite(step) && step < 1.0)
            s.distance_m += step;
        }
        last = xy;
      }
    }
    const mav::DecodeCounters& totals = decoder.totals();
    link.frames_received = totals.frames;
    link.crc_errors = totals.bad_crc;
    link.sequence_gaps = totals.sequence_gaps;
    link.other_errors = totals.bad_length + totals.unknown_id + totals.unsupported_flags +
                        totals.bad_signature + totals.replay_rejected + totals.unsigned_rejected;
    const double expected = static_cast<double>(totals.frames + totals.sequence_gaps);
    link.loss_percent =
        expected > 0.0 ? 100.0 * static_cast<double>(totals.sequence_gaps) / expected : 0.0;
    for (const RecordedEvent& e : recording.events) {
      if (e.text.find("link lost") != std::string::npos ||
          e.text.find("Link lost") != std::string::npos)
        ++link.link_losses;
    }
    if (pose_id) {
      const auto info = mav::findMessageInfo(*pose_id);
      s.distance_from = "odometry, " + std::string(info ? info->name : "pose");
    }
    s.link = std::move(link);
  }
  if (s.distance_from.empty() && recording.truth.size() >= 2) {
    for (std::size_t i = 1; i < recording.truth.size(); ++i) {
      const RecordedTruth& a = recording.truth[i - 1];
      const RecordedTruth& b = recording.truth[i];
      const double step = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
      if (std::isfinite(step) && step < 1.0)
        s.distance_m += step;
    }
    s.distance_from = "simulator truth";
  }
  return s;
}

std::string summaryMarkdown(const SessionSummary& s) {
  std::ostringstream out;
  out << "# " << s.title << "\n\n| | |\n| --- | --- |\n";
  for (const auto& [label, value] : overview(s))
    out << "| " << mdCell(label) << " | " << mdCell(value) << " |\n";
  if (s.link) {
    out << "\n## Link quality\n\n| | |\n| --- | --- |\n";
    for (const auto& [label, value] : linkRows(*s.link))
      out << "| " << label << " | " << value << " |\n";
    if (!s.link->messages.empty()) {
      out << "\n| message | received |\n| --- | ---: |\n";
      for (const auto& [name, n] : s.link->messages)
        out << "| " << mdCell(name) << " | " << n << " |\n";
    }
  }
  out << "\n## Events\n\n";
  if (s.events.empty()) {
    out << "No warnings, errors or link events.\n";
  } else {
    out << "| t (s) | kind | text |\n| ---: | --- | --- |\n";
    for (std::size_t i = 0; i < s.events.size() && i < kMaxListedEvents; ++i) {
      const SummaryEvent& e = s.events[i];
      out << "| " << fixed(e.t_s, 2) << " | " << mdCell(e.kind) << " | " << mdCell(e.text)
          << " |\n";
    }
    if (s.events.size() > kMaxListedEvents)
      out << "\n… and " << s.events.size() - kMaxListedEvents << " more.\n";
  }
  return out.str();
}

std::string summaryHtml(const SessionSummary& s) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << htmlEscape(s.title)
      << "</title>\n<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;"
         "margin-bottom:1.5em}td,th{border:1px solid #bbb;padding:3px 8px;text-align:left}"
         "th{background:#eee}.warning{color:#a60}.error{color:#b00}</style></head><body>\n";
  out << "<h1>" << htmlEscape(s.title) << "</h1>\n<table>\n";
  for (const auto& [label, value] : overview(s))
    out << "<tr><th>" << htmlEscape(label) << "</th><td>" << htmlEscape(value) << "</td></tr>\n";
  out << "</table>\n";
  if (s.link) {
    out << "<h2>Link quality</h2>\n<table>\n";
    for (const auto& [label, value] : linkRows(*s.link))
      out << "<tr><th>" << label << "</th><td>" << value << "</td></tr>\n";
    out << "</table>\n";
    if (!s.link->messages.empty()) {
      out << "<table><tr><th>message</th><th>received</th></tr>\n";
      for (const auto& [name, n] : s.link->messages)
        out << "<tr><td>" << htmlEscape(name) << "</td><td>" << n << "</td></tr>\n";
      out << "</table>\n";
    }
  }
  out << "<h2>Events</h2>\n";
  if (s.events.empty()) {
    out << "<p>No warnings, errors or link events.</p>\n";
  } else {
    out << "<table><tr><th>t (s)</th><th>kind</th><th>text</th></tr>\n";
    for (std::size_t i = 0; i < s.events.size() && i < kMaxListedEvents; ++i) {
      const SummaryEvent& e = s.events[i];
      out << "<tr class=\"" << htmlEscape(e.kind) << "\"><td>" << fixed(e.t_s, 2) << "</td><td>"
          << htmlEscape(e.kind) << "</td><td>" << htmlEscape(e.text) << "</td></tr>\n";
    }
    out << "</table>\n";
    if (s.events.size() > kMaxListedEvents)
      out << "<p>… and " << s.events.size() - kMaxListedEvents << " more.</p>\n";
  }
  out << "</body></html>\n";
  return out.str();
}

std::string writeSummary(const SessionSummary& summary, const std::string& path) {
  auto endsWith = [&](const std::string& suffix) {
    if (path.size() < suffix.size())
      return false;
    return std::equal(suffix.rbegin(), suffix.rend(), path.rbegin(), [](char a, char b) {
      return std::tolower(static_cast<unsigned char>(a)) ==
             std::tolower(static_cast<unsigned char>(b));
    });
  };
  std::string text;
  if (endsWith(".md") || endsWith(".markdown"))
    text = summaryMarkdown(summary);
  else if (endsWith(".html") || endsWith(".htm"))
    text = summaryHtml(summary);
  else
    return "a summary is written as .md (Markdown) or .html: " + path;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
    return "cannot write " + path;
  out << text;
  out.flush();
  if (!out)
    return "cannot write " + path;
  return {};
}

}  // namespace irgs::recording
