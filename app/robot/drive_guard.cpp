#include "app/robot/drive_guard.hpp"

#include <cmath>
#include <stdexcept>

namespace irgs::app {

DriveGuard::DriveGuard(double grace_s, double report_period_s)
    : grace_s_(grace_s), report_period_s_(report_period_s) {
  if (!(grace_s > 0.0) || !std::isfinite(grace_s) || !(report_period_s >= 0.0) ||
      !std::isfinite(report_period_s))
    throw std::invalid_argument("DriveGuard: grace must be > 0 and the report period >= 0");
}

void DriveGuard::peerAttached(double now_s) {
  attached_at_s_ = now_s;
  waiting_for_peer_ = false;
}

void DriveGuard::peerBytes(double now_s) {
  if (waiting_for_peer_)
    peerAttached(now_s);
}

bool DriveGuard::peerActive(double now_s, bool alive) {
  const bool active = alive || (!waiting_for_peer_ && now_s - attached_at_s_ < grace_s_);
  if (!active)
    waiting_for_peer_ = true;
  return active;
}

std::optional<std::string> DriveGuard::refused(const std::string& peer, double now_s) {
  ++refused_total_;
  last_refused_ = peer;
  if (next_report_s_ && now_s < *next_report_s_)
    return std::nullopt;
  return report(now_s);
}

std::optional<std::string> DriveGuard::dueReport(double now_s) {
  if (reported_total_ == refused_total_ || (next_report_s_ && now_s < *next_report_s_))
    return std::nullopt;
  return report(now_s);
}

std::string DriveGuard::report(double now_s) {
  reported_total_ = refused_total_;
  next_report_s_ = now_s + report_period_s_;
  return "refused client " + last_refused_ + " (" + std::to_string(refused_total_) + " total)";
}

}  // namespace irgs::app
