#include "comms/robot/param_client.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace irgs::comms {
namespace mav = mavlink;
namespace {

std::string nameOf(const std::array<char, 16>& field) {
  const auto end = std::find(field.begin(), field.end(), '\0');
  return std::string(field.begin(), end);
}

std::array<char, 16> fieldOf(const std::string& name) {
  std::array<char, 16> field{};
  std::memcpy(field.data(), name.data(), std::min(name.size(), field.size()));
  return field;
}

}  // namespace

const char* toString(ParamWriteStatus status) {
  switch (status) {
    case ParamWriteStatus::kAccepted:
      return "accepted";
    case ParamWriteStatus::kRejected:
      return "rejected";
    case ParamWriteStatus::kTimedOut:
      return "timed out";
  }
  return "?";
}

void ParamClient::requestAll(double now_s) {
  mav::ParamRequestList request;
  request.target_system = target_;
  outgoing_.emplace_back(request);
  reading_ = true;
  read_rounds_ = 0;
  last_value_s_ = now_s;
}

mav::ParamSet ParamClient::setMessage(const PendingWrite& write) const {
  mav::ParamSet message;
  message.target_system = target_;
  message.param_id = fieldOf(write.name);
  message.param_value = write.value;
  message.param_type = static_cast<std::uint8_t>(mav::MavParamType::kReal32);
  return message;
}

void ParamClient::set(const std::string& name, double value, double now_s) {
  if (name.empty() || name.size() > 16)
    throw std::invalid_argument("parameter names are 1 to 16 characters: '" + name + "'");
  if (!std::isfinite(value))
    throw std::invalid_argument("parameter " + name + ": the value must be finite");
  std::erase_if(writes_, [&](const PendingWrite& w) { return w.name == name; });
  PendingWrite write{name, static_cast<float>(value), now_s, 1};
  outgoing_.emplace_back(setMessage(write));
  writes_.push_back(std::move(write));
}

void ParamClient::onParamValue(const mav::ParamValue& message, double now_s) {
  const std::string name = nameOf(message.param_id);
  if (name.empty())
    return;
  const int index = message.param_index == 0xFFFF ? -1 : static_cast<int>(message.param_index);
  auto it = std::find_if(entries_.begin(), entries_.end(),
                         [&](const ParamEntry& e) { return e.name == name; });
  if (it == entries_.end())
    it = entries_.insert(entries_.end(), ParamEntry{name, 0.0, 0, -1});
  it->value = message.param_value;
  it->type = message.param_type;
  if (index >= 0)
    it->index = index;
  expected_ = message.param_count;
  last_value_s_ = now_s;
  if (reading_ && complete())
    reading_ = false;

  const auto write = std::find_if(writes_.begin(), writes_.end(),
                                  [&](const PendingWrite& w) { return w.name == name; });
  if (write != writes_.end()) {
    ParamWriteResult result;
    result.name = name;
    result.requested = write->value;
    result.applied = message.param_value;
    result.status = message.param_value == write->value ? ParamWriteStatus::kAccepted
                                                        : ParamWriteStatus::kRejected;
    results_.push_back(std::move(result));
    writes_.erase(write);
  }
}

void ParamClient::tick(double now_s) {
  if (reading_ && now_s - last_value_s_ >= kRetry_s) {
    if (read_rounds_ >= kMaxRetries) {
      reading_ = false;
    } else {
      ++read_rounds_;
      last_value_s_ = now_s;
      if (expected_ == 0) {
        mav::ParamRequestList request;
        request.target_system = target_;
        outgoing_.emplace_back(request);
      }
      for (int i = 0; i < expected_; ++i) {
        if (std::none_of(entries_.begin(), entries_.end(),
                         [&](const ParamEntry& e) { return e.index == i; })) {
          mav::ParamRequestRead read;
          read.target_system = target_;
          read.param_index = static_cast<std::int16_t>(i);
          outgoing_.emplace_back(read);
        }
      }
    }
  }
  for (auto it = writes_.begin(); it != writes_.end();) {
    if (now_s - it->sent_s < kRetry_s) {
      ++it;
      continue;
    }
    if (it->tries > kMaxRetries) {
      results_.push_back({it->name, it->value, std::nullopt, ParamWriteStatus::kTimedOut});
      it = writes_.erase(it);
      continue;
    }
    ++it->tries;
    it->sent_s = now_s;
    outgoing_.emplace_back(setMessage(*it));
    ++it;
  }
}

std::vector<ParamOutgoing> ParamClient::takeOutgoing() {
  return std::exchange(outgoing_, {});
}

std::vector<ParamWriteResult> ParamClient::takeResults() {
  return std::exchange(results_, {});
}

std::vector<ParamEntry> ParamClient::params() const {
  std::vector<ParamEntry> out = entries_;
  std::stable_sort(out.begin(), out.end(), [](const ParamEntry& a, const ParamEntry& b) {
    if ((a.index < 0) != (b.index < 0))
      return b.index < 0;
    return a.index != b.index ? a.index < b.index : a.name < b.name;
  });
  return out;
}

std::optional<ParamEntry> ParamClient::find(const std::string& name) const {
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [&](const ParamEntry& e) { return e.name == name; });
  if (it == entries_.end())
    return std::nullopt;
  return *it;
}

bool ParamClient::complete() const {
  if (expected_ <= 0)
    return false;
  for (int i = 0; i < expected_; ++i) {
    if (std::none_of(entries_.begin(), entries_.end(),
                     [&](const ParamEntry& e) { return e.index == i; }))
      return false;
  }
  return true;
}

}  // namespace irgs::comms
