#include "comms/link/command_manager.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace irgs::comms {

namespace mav = mavlink;

std::string commandName(std::uint16_t command) {
  switch (static_cast<mav::MavCmd>(command)) {
    case mav::MavCmd::kNavWaypoint:
      return "NAV_WAYPOINT";
    case mav::MavCmd::kDoSetMode:
      return "DO_SET_MODE";
    case mav::MavCmd::kMissionStart:
      return "MISSION_START";
    case mav::MavCmd::kComponentArmDisarm:
      return "COMPONENT_ARM_DISARM";
    case mav::MavCmd::kSetMessageInterval:
      return "SET_MESSAGE_INTERVAL";
    case mav::MavCmd::kRequestMessage:
      return "REQUEST_MESSAGE";
    case mav::MavCmd::kIrgsMoveDistance:
      return "IRGS_MOVE_DISTANCE";
    case mav::MavCmd::kIrgsTurnAngle:
      return "IRGS_TURN_ANGLE";
    case mav::MavCmd::kIrgsFollowWall:
      return "IRGS_FOLLOW_WALL";
    case mav::MavCmd::kIrgsStop:
      return "IRGS_STOP";
    case mav::MavCmd::kIrgsEmergencyStop:
      return "IRGS_EMERGENCY_STOP";
  }
  return "MAV_CMD " + std::to_string(command);
}

std::string resultName(std::uint8_t result) {
  switch (static_cast<mav::MavResult>(result)) {
    case mav::MavResult::kAccepted:
      return "ACCEPTED";
    case mav::MavResult::kTemporarilyRejected:
      return "TEMPORARILY_REJECTED";
    case mav::MavResult::kDenied:
      return "DENIED";
    case mav::MavResult::kUnsupported:
      return "UNSUPPORTED";
    case mav::MavResult::kFailed:
      return "FAILED";
    case mav::MavResult::kInProgress:
      return "IN_PROGRESS";
    case mav::MavResult::kCancelled:
      return "CANCELLED";
    case mav::MavResult::kCommandLongOnly:
      return "COMMAND_LONG_ONLY";
    case mav::MavResult::kCommandIntOnly:
      return "COMMAND_INT_ONLY";
    case mav::MavResult::kCommandUnsupportedMavFrame:
      return "COMMAND_UNSUPPORTED_MAV_FRAME";
    case mav::MavResult::kNotInControl:
      return "NOT_IN_CONTROL";
  }
  return "MAV_RESULT " + std::to_string(result);
}

namespace {

std::string timing(int attempts, double elapsed_s) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%d attempt%s, %.2f s", attempts, attempts == 1 ? "" : "s",
                elapsed_s);
  return buffer;
}

bool positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

}  // namespace

CommandManager::CommandManager(CommandConfig config) : config_(config) {
  if (!positive(config_.retry_s) || !positive(config_.in_progress_timeout_s) ||
      config_.max_attempts < 1)
    throw std::invalid_argument(
        "CommandConfig: retry_s and in_progress_timeout_s must be > 0 and max_attempts >= 1");
}

void CommandManager::submit(mav::CommandLong command, CommandCallback callback, double now_s,
                            std::vector<mav::CommandLong>& out) {
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (pending_[i].command.command == command.command) {
      finish(i, CommandOutcome::kCancelled, std::nullopt, "superseded by a newer one", now_s);
      break;  // at most one per id
    }
  }
  command.confirmation = 0;
  Pending p;
  p.command = command;
  p.callback = std::move(callback);
  p.first_sent_s = now_s;
  p.next_action_s = now_s + config_.retry_s;
  p.attempts = 1;
  pending_.push_back(std::move(p));
  out.push_back(command);
}

bool CommandManager::onAck(const mav::CommandAck& ack, std::uint8_t system_id,
                           std::uint8_t own_system, std::uint8_t own_component, double now_s) {
  // Acks addressed to another ground station (target fields are an extension: 0 = unset).
  if ((ack.target_system != 0 && ack.target_system != own_system) ||
      (ack.target_component != 0 && ack.target_component != own_component))
    return false;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    auto& p = pending_[i];
    if (p.command.command != ack.command)
      continue;
    if (p.command.target_system != 0 && p.command.target_system != system_id)
      continue;
    if (ack.result == static_cast<std::uint8_t>(mav::MavResult::kInProgress)) {
      p.in_progress = true;
      p.next_action_s = now_s + config_.in_progress_timeout_s;
      return true;
    }
    if (ack.result == static_cast<std::uint8_t>(mav::MavResult::kAccepted))
      finish(i, CommandOutcome::kAccepted, ack.result, "", now_s);
    else
      finish(i, CommandOutcome::kRejected, ack.result, resultName(ack.result), now_s);
    return true;
  }
  return false;
}

void CommandManager::tick(double now_s, std::vector<mav::CommandLong>& out) {
  for (std::size_t i = 0; i < pending_.size();) {
    auto& p = pending_[i];
    if (now_s < p.next_action_s) {
      ++i;
      continue;
    }
    if (p.in_progress) {
      finish(i, CommandOutcome::kTimedOut, std::nullopt, "no final COMMAND_ACK after IN_PROGRESS",
             now_s);
      continue;
    }
    if (p.attempts >= config_.max_attempts) {
      finish(i, CommandOutcome::kTimedOut, std::nullopt, "no COMMAND_ACK", now_s);
      continue;
    }
    p.command.confirmation = static_cast<std::uint8_t>(std::min(p.attempts, 255));
    ++p.attempts;
    p.next_action_s = now_s + config_.retry_s;
    out.push_back(p.command);
    ++i;
  }
}

void CommandManager::cancelAll(const std::string& reason, double now_s) {
  while (!pending_.empty())
    finish(0, CommandOutcome::kCancelled, std::nullopt, reason, now_s);
}

std::vector<CompletedCommand> CommandManager::takeCompleted() {
  std::vector<CompletedCommand> out;
  out.swap(completed_);
  return out;
}

void CommandManager::finish(std::size_t index, CommandOutcome outcome,
                            std::optional<std::uint8_t> result, std::string detail, double now_s) {
  Pending p = std::move(pending_[index]);
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
  CommandResult r;
  r.command = p.command.command;
  r.outcome = outcome;
  r.mav_result = result;
  r.attempts = p.attempts;
  r.elapsed_s = std::max(0.0, now_s - p.first_sent_s);
  r.message = commandName(r.command) + " " + std::string(toString(outcome));
  if (!detail.empty())
    r.message += ": " + detail;
  r.message += " (" + timing(r.attempts, r.elapsed_s) + ")";
  completed_.push_back({std::move(r), std::move(p.callback)});
}

}  // namespace irgs::comms
