#pragma once
// The ground side of the MAVLink parameter protocol (https://mavlink.io/en/services/
// parameter.html; the robot side is app/robot/firmware_params.hpp, docs/protocol.md section 12):
// read all parameters, read one, write one and confirm it. Pure and single-threaded: the caller
// feeds PARAM_VALUE messages and the time, and sends what takeOutgoing() returns (LinkedRobot
// does both on its io thread).
//
// Reading all: PARAM_REQUEST_LIST; values arrive as PARAM_VALUE with param_index/param_count.
// Indices still missing kRetry_s after the last value are asked for one by one with
// PARAM_REQUEST_READ (by index), up to kMaxRetries rounds.
//
// Writing: PARAM_SET (REAL32); the robot answers with PARAM_VALUE carrying the value now in
// force. The write is kAccepted when that value equals the requested one (as a float), kRejected
// when the robot kept another value (out of range: its STATUSTEXT says why) and kTimedOut when no
// PARAM_VALUE of that name arrived after kMaxRetries resends.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "comms/mavlink/messages.hpp"

namespace irgs::comms {

struct ParamEntry {
  std::string name;
  double value = 0.0;
  std::uint8_t type = 0;  // MAV_PARAM_TYPE
  int index = -1;
};

enum class ParamWriteStatus { kAccepted, kRejected, kTimedOut };
const char* toString(ParamWriteStatus status);

struct ParamWriteResult {
  std::string name;
  double requested = 0.0;
  std::optional<double> applied;  // the value the robot reported (none when timed out)
  ParamWriteStatus status = ParamWriteStatus::kTimedOut;
};

using ParamOutgoing =
    std::variant<mavlink::ParamRequestList, mavlink::ParamRequestRead, mavlink::ParamSet>;

class ParamClient {
 public:
  static constexpr double kRetry_s = 0.5;
  static constexpr int kMaxRetries = 3;

  // Parameters requested from `target_system` (0 until the robot is known; setTarget()).
  explicit ParamClient(std::uint8_t target_system = 0) : target_(target_system) {}
  void setTarget(std::uint8_t target_system) { target_ = target_system; }

  // Starts reading every parameter (the table is kept; values are updated as they arrive).
  void requestAll(double now_s);
  // Writes a parameter. Throws std::invalid_argument for a name longer than 16 characters or a
  // non-finite value. A second write of the same name replaces the first (one result).
  void set(const std::string& name, double value, double now_s);

  // Feed every PARAM_VALUE from the robot.
  void onParamValue(const mavlink::ParamValue& message, double now_s);
  // Retries; call periodically (every ~0.1 s).
  void tick(double now_s);

  std::vector<ParamOutgoing> takeOutgoing();
  std::vector<ParamWriteResult> takeResults();

  // The parameters received, by index (then name for index-less ones).
  std::vector<ParamEntry> params() const;
  std::optional<ParamEntry> find(const std::string& name) const;
  // param_count of the last PARAM_VALUE (0 before any).
  int expectedCount() const { return expected_; }
  // True once every index 0..expectedCount()-1 has arrived.
  bool complete() const;
  // True while a read-all is still waiting for values (and has retries left).
  bool reading() const { return reading_; }
  bool writing() const { return !writes_.empty(); }

 private:
  struct PendingWrite {
    std::string name;
    float value = 0.0F;
    double sent_s = 0.0;
    int tries = 1;
  };
  mavlink::ParamSet setMessage(const PendingWrite& write) const;

  std::uint8_t target_ = 0;
  std::vector<ParamEntry> entries_;  // in arrival order; indexed lookups scan (a few dozen)
  int expected_ = 0;
  bool reading_ = false;
  double last_value_s_ = 0.0;
  int read_rounds_ = 0;
  std::vector<PendingWrite> writes_;
  std::vector<ParamOutgoing> outgoing_;
  std::vector<ParamWriteResult> results_;
};

}  // namespace irgs::comms
