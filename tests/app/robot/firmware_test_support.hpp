#pragma once
// Test support for FirmwareCore: a fake ground station that encodes MAVLink frames with its own
// FrameEncoder and decodes what the firmware sends, driven by a fake clock (no sleeps); the
// thesis robot and a 6 m room.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/robot/firmware_core.hpp"
#include "comms/mavlink/messages.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"

namespace irgs::app::firmware_test {

namespace mav = comms::mavlink;

inline RobotProfile thesisRobot() {
  auto result =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!result.profile)
    throw std::runtime_error("thesis robot profile missing");
  return *result.profile;
}

// A 6 m square room; optionally a wall across the path 0.4 m ahead of the start.
inline WorldMap room(bool wall_ahead, Pose2 start = {}) {
  WorldMap map;
  Wall box;
  box.id = "box";
  box.points = {Vec2(-3, -3), Vec2(3, -3), Vec2(3, 3), Vec2(-3, 3)};
  box.closed = true;
  map.walls.push_back(box);
  if (wall_ahead) {
    Wall w;
    w.id = "ahead";
    w.points = {Vec2(start.x + 0.4, -1.0), Vec2(start.x + 0.4, 1.0)};
    map.walls.push_back(w);
  }
  map.start = start;
  return map;
}

struct Received {
  double t_s;
  mav::Frame frame;
};

class Gcs {
 public:
  explicit Gcs(FirmwareCore& core) : core_(core) {}

  template <class M>
  void send(const M& message, double t) {
    core_.receiveBytes(encoder_.encode(message).view(), t);
  }
  void heartbeat(double t) {
    mav::Heartbeat hb;
    hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
    send(hb, t);
  }
  void manual(std::int16_t x, std::int16_t r, double t) {
    mav::ManualControl mc;
    mc.target = 1;
    mc.x = x;
    mc.r = r;
    send(mc, t);
  }
  void command(mav::MavCmd cmd, float param1, double t) {
    mav::CommandLong c;
    c.target_system = 1;
    c.command = static_cast<std::uint16_t>(cmd);
    c.param1 = param1;
    send(c, t);
  }

  // Runs the clock from now_ to `until` in 10 ms ticks, sending heartbeats (every 0.5 s) and
  // MANUAL_CONTROL (every 0.1 s) when asked, and collecting what the firmware sends.
  void run(double until, bool heartbeats, std::optional<std::pair<std::int16_t, std::int16_t>> mc) {
    while (now_ + 1e-9 < until) {
      now_ += 0.01;
      if (heartbeats && now_ + 1e-9 >= next_hb_) {
        heartbeat(now_);
        next_hb_ = now_ + 0.5;
      }
      if (mc && now_ + 1e-9 >= next_mc_) {
        manual(mc->first, mc->second, now_);
        next_mc_ = now_ + 0.1;
      }
      core_.advance(now_);
      const auto bytes = core_.takeOutput();
      frames_.clear();
      decoder_.feed(bytes, frames_);
      for (const auto& f : frames_)
        received.push_back({now_, f});
    }
  }

  template <class M>
  std::vector<M> all(double from = -1.0) const {
    std::vector<M> out;
    for (const auto& r : received)
      if (r.t_s > from)
        if (auto m = r.frame.as<M>())
          out.push_back(*m);
    return out;
  }
  bool saidSomething(const std::string& needle) const {
    for (const auto& s : all<mav::Statustext>())
      if (std::string(s.text.data(), strnlen(s.text.data(), s.text.size())).find(needle) !=
          std::string::npos)
        return true;
    return false;
  }

  double now() const { return now_; }
  std::vector<Received> received;

 private:
  FirmwareCore& core_;
  mav::FrameEncoder encoder_{255, 190};
  mav::FrameDecoder decoder_;
  std::vector<mav::Frame> frames_;
  double now_ = 0.0;
  double next_hb_ = 0.0;
  double next_mc_ = 0.0;
};

inline FirmwareCore makeCore(WorldMap map, FirmwareConfig config = {}) {
  SimConfig sim;
  sim.seed = 7;
  return FirmwareCore(Simulator(std::move(map), thesisRobot(), idealSimConfig(sim)), config);
}

// The thesis robot without bumpers: only the sonars and the watchdogs can tell it is blocked.
inline FirmwareCore makeBumperlessCore(WorldMap map) {
  RobotProfile profile = thesisRobot();
  profile.bumpers.clear();
  SimConfig sim;
  sim.seed = 7;
  return FirmwareCore(Simulator(std::move(map), profile, idealSimConfig(sim)));
}

inline bool stopped(const FirmwareCore& core) {
  const auto v = core.simulator().trueVelocity();
  return v.linear_mps == 0.0 && v.angular_radps == 0.0;
}

// The COMMAND_ACKs of one command, in order.
inline std::vector<mav::CommandAck> acksFor(const Gcs& gcs, mav::MavCmd command) {
  std::vector<mav::CommandAck> out;
  for (const auto& a : gcs.all<mav::CommandAck>())
    if (a.command == static_cast<std::uint16_t>(command))
      out.push_back(a);
  return out;
}

inline std::vector<std::uint8_t> behaviourStates(const Gcs& gcs) {
  std::vector<std::uint8_t> states;
  for (const auto& b : gcs.all<mav::IrgsBehaviourStatus>())
    states.push_back(b.state);
  return states;
}

inline constexpr auto kRunning = static_cast<std::uint8_t>(mav::IrgsBehaviourState::kRunning);
inline constexpr auto kSucceeded = static_cast<std::uint8_t>(mav::IrgsBehaviourState::kSucceeded);
inline constexpr auto kAborted = static_cast<std::uint8_t>(mav::IrgsBehaviourState::kAborted);

}  // namespace irgs::app::firmware_test
