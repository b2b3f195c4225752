#pragma once
// The virtual Pioneer (app/robot ArcosFirmware) served in-process on the master side of a real
// pseudo-terminal pair, for ArcosRobot tests: a thread steps the firmware in wall-clock time
// (10 ms), feeds it what the client wrote and writes its output. stop() closes both ends, as a
// robot that vanished. Test support, not a product.

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/robot/arcos_firmware.hpp"

namespace irgs::comms::testing {

class ArcosPtyServer {
 public:
  using Clock = std::chrono::steady_clock;

  ArcosPtyServer(std::unique_ptr<app::ArcosFirmware> firmware, std::filesystem::path symlink = {})
      : firmware_(std::move(firmware)), symlink_(std::move(symlink)) {
    termios raw{};
    ::cfmakeraw(&raw);
    char name[256] = {};
    if (::openpty(&master_, &slave_, name, &raw, nullptr) != 0)
      throw std::runtime_error("openpty failed");
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    slave_path_ = name;
    if (!symlink_.empty()) {
      std::error_code ec;
      std::filesystem::remove(symlink_, ec);
      std::filesystem::create_symlink(slave_path_, symlink_);
    }
    thread_ = std::thread([this] { run(); });
  }
  ~ArcosPtyServer() { stop(); }
  ArcosPtyServer(const ArcosPtyServer&) = delete;
  ArcosPtyServer& operator=(const ArcosPtyServer&) = delete;

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

  std::string url() const {
    const std::string device = symlink_.empty() ? slave_path_ : symlink_.string();
    return "serial://" + device + "?baud=115200&protocol=arcos";
  }

  // Snapshots taken under the lock after every step.
  Pose2 reportedPose() const {
    const std::lock_guard lock(mutex_);
    return reported_pose_;
  }
  VelocityCommand trueVelocity() const {
    const std::lock_guard lock(mutex_);
    return true_velocity_;
  }
  app::ArcosFirmwareStats stats() const {
    const std::lock_guard lock(mutex_);
    return stats_;
  }
  app::ArcosServerState state() const {
    const std::lock_guard lock(mutex_);
    return state_;
  }

 private:
  void run() {
    const Clock::time_point start = Clock::now();
    Clock::time_point next = start;
    std::vector<std::uint8_t> rx(4096);
    std::vector<std::uint8_t> pending;
    while (!stop_) {
      next += std::chrono::milliseconds(10);
      std::this_thread::sleep_until(next);  // the firmware's clock, not a test wait
      const double now_s = std::chrono::duration<double>(Clock::now() - start).count();
      for (;;) {
        const ssize_t n = ::read(master_, rx.data(), rx.size());
        if (n <= 0)
          break;
        firmware_->receiveBytes(
            std::span<const std::uint8_t>(rx.data(), static_cast<std::size_t>(n)), now_s);
      }
      firmware_->advance(now_s);
      const std::vector<std::uint8_t> out = firmware_->takeOutput();
      pending.insert(pending.end(), out.begin(), out.end());
      if (pending.size() > 64 * 1024)
        pending.clear();  // nobody reads the slave
      if (!pending.empty()) {
        const ssize_t n = ::write(master_, pending.data(), pending.size());
        if (n > 0)
          pending.erase(pending.begin(), pending.begin() + n);
      }
      const std::lock_guard lock(mutex_);
      reported_pose_ = firmware_->reportedPose();
      true_velocity_ = firmware_->simulator().trueVelocity();
      stats_ = firmware_->stats();
      state_ = firmware_->state();
    }
  }

  std::unique_ptr<app::ArcosFirmware> firmware_;
  std::filesystem::path symlink_;
  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  Pose2 reported_pose_;
  VelocityCommand true_velocity_;
  app::ArcosFirmwareStats stats_;
  app::ArcosServerState state_ = app::ArcosServerState::kWaitSync0;
  std::thread thread_;  // last: started after everything it uses exists
};

}  // namespace irgs::comms::testing
