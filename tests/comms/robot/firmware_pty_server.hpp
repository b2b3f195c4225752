#pragma once
// The virtual robot firmware (app/robot FirmwareCore) served in-process on the master side of a
// real pseudo-terminal pair, for LinkedRobot tests and the latency bench: a thread steps the
// firmware one simulator step (dt) at a time in wall-clock time, feeds it what the ground station
// wrote and writes its output paced like a UART (bytes_per_s, e.g. 11520 for 115200 baud 8N1).
// It records, for checks, every odometry pose the firmware had at each step, the sonar frames it
// emitted and the wall time at which each odometry time stamp started going out on the wire, and
// when each MANUAL_CONTROL arrived from the ground station (the rate on the wire).
// Test support, not a product: no gtest in here so the bench can use it too.

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/robot/firmware_core.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::comms::testing {

class FirmwarePtyServer {
 public:
  using Clock = std::chrono::steady_clock;

  struct Options {
    double bytes_per_s = 11520.0;   // 115200 baud 8N1; 0 = unlimited
    std::filesystem::path symlink;  // optional stable name for the slave (replaced if present)
  };

  struct SonarFrame {
    int sensor = 0;
    std::uint16_t distance_cm = 0;
    std::uint16_t max_cm = 0;
  };

  FirmwarePtyServer(std::unique_ptr<app::FirmwareCore> core, Options options)
      : core_(std::move(core)), options_(std::move(options)) {
    termios raw{};
    ::cfmakeraw(&raw);
    char name[256] = {};
    if (::openpty(&master_, &slave_, name, &raw, nullptr) != 0)
      throw std::runtime_error("openpty failed");
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    slave_path_ = name;
    if (!options_.symlink.empty()) {
      std::error_code ec;
      std::filesystem::remove(options_.symlink, ec);
      std::filesystem::create_symlink(slave_path_, options_.symlink);
    }
    thread_ = std::thread([this] { run(); });
  }

  ~FirmwarePtyServer() { stop(); }
  FirmwarePtyServer(const FirmwarePtyServer&) = delete;
  FirmwarePtyServer& operator=(const FirmwarePtyServer&) = delete;

  // Stops the firmware and closes both ends: the ground station's port fails (a robot that
  // vanished). Idempotent.
  void stop() {
    stop_ = true;
    if (thread_.joinable())
      thread_.join();
    if (master_ >= 0)
      ::close(master_);
    if (slave_ >= 0)
      ::close(slave_);
    master_ = slave_ = -1;
  }

  const std::string& slavePath() const { return slave_path_; }
  std::string url() const {
    const std::string device = options_.symlink.empty() ? slave_path_ : options_.symlink.string();
    return "serial://" + device + "?baud=115200";
  }

  // The firmware's odometry pose after the step that ended at `time_ms` (robot boot time).
  std::optional<Pose2> odometryAt(std::int64_t time_ms) const {
    const std::lock_guard lock(mutex_);
    const auto it = odometry_.find(time_ms);
    if (it == odometry_.end())
      return std::nullopt;
    return it->second;
  }
  // Sonar frames (DISTANCE_SENSOR) the firmware emitted for `time_ms`.
  std::vector<SonarFrame> sonarAt(std::int64_t time_ms) const {
    const std::lock_guard lock(mutex_);
    const auto it = sonar_.find(time_ms);
    return it == sonar_.end() ? std::vector<SonarFrame>{} : it->second;
  }
  // Wall time at which the step carrying odometry time stamp `time_ms` started to be written.
  std::optional<Clock::time_point> emittedAt(std::int64_t time_ms) const {
    const std::lock_guard lock(mutex_);
    const auto it = emitted_.find(time_ms);
    if (it == emitted_.end())
      return std::nullopt;
    return it->second;
  }
  Pose2 truePose() const {
    const std::lock_guard lock(mutex_);
    return true_pose_;
  }
  app::SafetyState safety() const {
    const std::lock_guard lock(mutex_);
    return safety_;
  }
  // The firmware's parameter table after the last step (what it applied).
  app::ParamTable params() const {
    const std::lock_guard lock(mutex_);
    return params_;
  }
  std::uint64_t droppedBytes() const { return dropped_bytes_.load(); }
  // Seconds since the server started at which each MANUAL_CONTROL was read from the pty.
  std::vector<double> manualControlArrivals() const {
    const std::lock_guard lock(mutex_);
    return manual_controls_;
  }

 private:
  static std::int64_t toMs(double t_s) { return std::llround(t_s * 1000.0); }

  void run() {
    const double dt = core_->simulator().config().dt_s;
    const Clock::time_point start = Clock::now();
    Clock::time_point last_write = start;
    std::vector<std::uint8_t> rx(4096);
    mavlink::FrameDecoder tap;     // decodes our own output for the records
    mavlink::FrameDecoder rx_tap;  // and what the ground station wrote
    std::vector<mavlink::Frame> frames;
    std::uint64_t queued_total = 0;   // bytes ever queued
    std::uint64_t written_total = 0;  // bytes ever written
    struct Mark {
      std::uint64_t offset;  // stream offset of the step's first byte
      std::int64_t time_ms;
    };
    std::vector<Mark> marks;  // odometry steps not yet on the wire
    double budget = 0.0;
    Clock::time_point next = start;
    while (!stop_) {
      next += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
      std::this_thread::sleep_until(next);  // the firmware's clock, not a test wait
      const Clock::time_point now = Clock::now();
      const double now_s = std::chrono::duration<double>(now - start).count();
      for (;;) {
        const ssize_t n = ::read(master_, rx.data(), rx.size());
        if (n <= 0)
          break;
        const std::span<const std::uint8_t> bytes(rx.data(), static_cast<std::size_t>(n));
        core_->receiveBytes(bytes, now_s);
        frames.clear();
        rx_tap.feed(bytes, frames);
        const std::lock_guard lock(mutex_);
        for (const auto& f : frames) {
          if (f.message_id == mavlink::ManualControl::kId)
            manual_controls_.push_back(now_s);
        }
      }
      // One step at a time so every step's pose and output can be recorded.
      while (core_->simulator().time_s() + 0.5 * dt <= now_s) {
        core_->advance(core_->simulator().time_s() + dt);
        const std::int64_t t_ms = toMs(core_->simulator().time_s());
        std::vector<std::uint8_t> out = core_->takeOutput();
        frames.clear();
        tap.feed(out, frames);
        const std::lock_guard lock(mutex_);
        odometry_[t_ms] = core_->simulator().odometryPose();
        true_pose_ = core_->simulator().truePose();
        safety_ = core_->safety();
        params_ = core_->params();
        bool has_pose = false;
        for (const auto& f : frames) {
          if (f.message_id == mavlink::LocalPositionNed::kId ||
              f.message_id == mavlink::IrgsPose2d::kId || f.message_id == mavlink::Odometry::kId)
            has_pose = true;
          if (const auto ds = f.as<mavlink::DistanceSensor>())
            sonar_[ds->time_boot_ms].push_back({ds->id, ds->current_distance, ds->max_distance});
        }
        if (out.empty())
          continue;
        const double limit = options_.bytes_per_s > 0 ? options_.bytes_per_s * 0.25 + 512 : 1e12;
        if (static_cast<double>(pending_.size() + out.size()) > limit) {
          dropped_bytes_ += out.size();  // a real UART link falls behind too
          continue;
        }
        if (has_pose)
          marks.push_back({queued_total, t_ms});
        queued_total += out.size();
        pending_.insert(pending_.end(), out.begin(), out.end());
      }
      std::size_t allowed = pending_.size();
      if (options_.bytes_per_s > 0) {
        const double elapsed = std::chrono::duration<double>(now - last_write).count();
        budget =
            std::min(budget + elapsed * options_.bytes_per_s, options_.bytes_per_s * 0.05 + 512);
        allowed = std::min(allowed, static_cast<std::size_t>(budget));
      }
      last_write = now;
      if (allowed == 0)
        continue;
      const ssize_t n = ::write(master_, pending_.data(), allowed);
      if (n <= 0)
        continue;  // EAGAIN: nobody reads the slave; retry next step
      const Clock::time_point written_at = Clock::now();
      pending_.erase(pending_.begin(), pending_.begin() + n);
      budget -= static_cast<double>(n);
      written_total += static_cast<std::uint64_t>(n);
      const std::lock_guard lock(mutex_);
      auto it = marks.begin();
      for (; it != marks.end() && it->offset < written_total; ++it)
        emitted_[it->time_ms] = written_at;
      marks.erase(marks.begin(), it);
    }
  }

  std::unique_ptr<app::FirmwareCore> core_;
  Options options_;
  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
  std::vector<std::uint8_t> pending_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> dropped_bytes_{0};

  mutable std::mutex mutex_;
  std::map<std::int64_t, Pose2> odometry_;
  std::map<std::int64_t, std::vector<SonarFrame>> sonar_;
  std::map<std::int64_t, Clock::time_point> emitted_;
  Pose2 true_pose_;
  app::SafetyState safety_;
  app::ParamTable params_;
  std::vector<double> manual_controls_;

  std::thread thread_;  // last: started after everything it uses exists
};

}  // namespace irgs::comms::testing
