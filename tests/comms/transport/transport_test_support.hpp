#pragma once
// Helpers for transport tests: a callback recorder that tests wait on (condition variable with a
// generous timeout, never a fixed sleep) and a raw pseudo-terminal pair.

#include "comms/transport/transport.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace irgs::comms::testing {

inline constexpr std::chrono::seconds kWait{10};  // generous: only reached when a test fails

class Recorder {
 public:
  TransportCallbacks callbacks() {
    TransportCallbacks cb;
    cb.on_bytes = [this](std::span<const std::uint8_t> bytes) {
      const std::lock_guard lock(mutex_);
      bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
      cv_.notify_all();
    };
    cb.on_state = [this](TransportState state, const std::string& message) {
      const std::lock_guard lock(mutex_);
      states_.push_back(state);
      messages_.push_back(message);
      cv_.notify_all();
    };
    cb.on_refused = [this](const std::string& peer) {
      const std::lock_guard lock(mutex_);
      refused_.push_back(peer);
      cv_.notify_all();
    };
    return cb;
  }

  // Waits until at least `count` peers have been refused.
  bool waitRefused(std::size_t count) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] { return refused_.size() >= count; });
  }
  std::vector<std::string> refused() const {
    const std::lock_guard lock(mutex_);
    return refused_;
  }

  // Waits until at least `count` bytes have arrived.
  bool waitBytes(std::size_t count) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] { return bytes_.size() >= count; });
  }
  // Waits until `state` has been reported at least `occurrences` times in total.
  bool waitState(TransportState state, std::size_t occurrences = 1) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] { return countLocked(state) >= occurrences; });
  }
  // Waits until the transport has either opened or failed.
  bool waitSettled() {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] {
      return countLocked(TransportState::kOpen) + countLocked(TransportState::kFailed) > 0;
    });
  }
  // Waits until a status message containing `text` has been reported.
  bool waitMessage(const std::string& text) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] {
      for (const auto& m : messages_)
        if (m.find(text) != std::string::npos)
          return true;
      return false;
    });
  }

  std::vector<std::uint8_t> bytes() const {
    const std::lock_guard lock(mutex_);
    return bytes_;
  }
  void clearBytes() {
    const std::lock_guard lock(mutex_);
    bytes_.clear();
  }
  std::size_t count(TransportState state) const {
    const std::lock_guard lock(mutex_);
    return countLocked(state);
  }
  std::string lastMessage() const {
    const std::lock_guard lock(mutex_);
    return messages_.empty() ? std::string{} : messages_.back();
  }
  std::string allMessages() const {
    const std::lock_guard lock(mutex_);
    std::string out;
    for (const auto& m : messages_)
      out += m + "\n";
    return out;
  }

 private:
  std::size_t countLocked(TransportState state) const {
    std::size_t n = 0;
    for (auto s : states_)
      n += s == state ? 1u : 0u;
    return n;
  }

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std::uint8_t> bytes_;
  std::vector<TransportState> states_;
  std::vector<std::string> messages_;
  std::vector<std::string> refused_;
};

// A raw pty pair. The transport opens slavePath(); the test drives masterFd().
class PtyPair {
 public:
  PtyPair() {
    termios raw{};
    cfmakeraw(&raw);
    char name[256] = {};
    if (::openpty(&master_, &slave_, name, &raw, nullptr) != 0)
      throw std::runtime_error("openpty failed");
    slave_path_ = name;
  }
  ~PtyPair() {
    closeMaster();
    if (slave_ >= 0)
      ::close(slave_);
  }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  const std::string& slavePath() const { return slave_path_; }
  int masterFd() const { return master_; }
  void closeMaster() {
    if (master_ >= 0)
      ::close(master_);
    master_ = -1;
  }

  bool writeAll(const std::vector<std::uint8_t>& data) const {
    std::size_t done = 0;
    while (done < data.size()) {
      if (!waitFd(POLLOUT))
        return false;
      const auto n = ::write(master_, data.data() + done, data.size() - done);
      if (n < 0 && errno != EAGAIN && errno != EINTR)
        return false;
      if (n > 0)
        done += static_cast<std::size_t>(n);
    }
    return true;
  }

  // Reads exactly `count` bytes (false on timeout or error).
  bool readExactly(std::size_t count, std::vector<std::uint8_t>& out) const {
    out.clear();
    std::vector<std::uint8_t> buffer(8192);
    while (out.size() < count) {
      if (!waitFd(POLLIN))
        return false;
      const auto n = ::read(master_, buffer.data(), std::min(buffer.size(), count - out.size()));
      if (n < 0 && errno != EAGAIN && errno != EINTR)
        return false;
      if (n > 0)
        out.insert(out.end(), buffer.begin(), buffer.begin() + n);
    }
    return true;
  }

 private:
  bool waitFd(short events) const {
    pollfd p{master_, events, 0};
    const int timeout_ms = static_cast<int>(std::chrono::milliseconds(kWait).count());
    return ::poll(&p, 1, timeout_ms) == 1 && (p.revents & events) != 0;
  }

  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
};

// Deterministic test payload: byte i is a function of i and the seed.
inline std::vector<std::uint8_t> pattern(std::size_t size, std::uint32_t seed) {
  std::vector<std::uint8_t> out(size);
  std::uint32_t x = seed * 2654435761u + 1u;
  for (auto& b : out) {
    x = x * 1664525u + 1013904223u;  // LCG (Numerical Recipes)
    b = static_cast<std::uint8_t>(x >> 24);
  }
  return out;
}

inline std::span<const std::uint8_t> asBytes(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

inline std::string asText(const std::vector<std::uint8_t>& bytes) {
  return {bytes.begin(), bytes.end()};
}

}  // namespace irgs::comms::testing
