#include "comms/arcos/arcos_sip.hpp"

#include <stdexcept>

namespace irgs::comms::arcos {
namespace {

// Reads little-endian fields and remembers the first one that ran past the end.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::optional<std::uint8_t> u8(const char* field) {
    if (!need(1, field))
      return std::nullopt;
    return bytes_[pos_++];
  }
  std::optional<std::uint16_t> u16(const char* field) {
    if (!need(2, field))
      return std::nullopt;
    const auto value = static_cast<std::uint16_t>(bytes_[pos_] | bytes_[pos_ + 1] << 8);
    pos_ += 2;
    return value;
  }
  std::optional<std::int16_t> i16(const char* field) {
    const auto value = u16(field);
    if (!value)
      return std::nullopt;
    return static_cast<std::int16_t>(*value);
  }
  const std::string& missing() const { return missing_; }

 private:
  bool need(std::size_t n, const char* field) {
    if (remaining() >= n)
      return true;
    if (missing_.empty())
      missing_ = field;
    return false;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  std::string missing_;
};

void put16(std::vector<std::uint8_t>& out, std::uint16_t value) {
  out.push_back(static_cast<std::uint8_t>(value & 0xFF));
  out.push_back(static_cast<std::uint8_t>(value >> 8));
}

}  // namespace

SipParseResult parseStandardSip(std::span<const std::uint8_t> payload) {
  SipParseResult result;
  Reader in(payload);
  StandardSip sip;
  const auto type = in.u8("TYPE");
  if (type && !isStandardSipType(*type)) {
    result.error = "not a standard SIP (type " + std::to_string(*type) + ")";
    return result;
  }
  const auto x = in.u16("XPOS");
  const auto y = in.u16("YPOS");
  const auto th = in.i16("THPOS");
  const auto lvel = in.i16("L VEL");
  const auto rvel = in.i16("R VEL");
  const auto battery = in.u8("BATTERY");
  const auto stall = in.u16("STALL AND BUMPERS");
  const auto control = in.i16("CONTROL");
  const auto flags = in.u16("FLAGS");
  const auto compass = in.u8("COMPASS");
  const auto count = in.u8("SONAR COUNT");
  if (!count) {
    result.error =
        "standard SIP of " + std::to_string(payload.size()) + " bytes ends before " + in.missing();
    return result;
  }
  if (*count > kMaxSonars) {
    result.error = "standard SIP announces " + std::to_string(*count) + " sonar readings (max 32)";
    return result;
  }
  sip.type = *type;
  sip.x_raw = static_cast<std::uint16_t>(*x & 0x7FFF);
  sip.y_raw = static_cast<std::uint16_t>(*y & 0x7FFF);
  sip.theta_raw = *th;
  sip.left_velocity = *lvel;
  sip.right_velocity = *rvel;
  sip.battery_decivolts = *battery;
  sip.stall_and_bumpers = *stall;
  sip.control = *control;
  sip.flags = *flags;
  sip.compass = *compass;
  sip.sonars.reserve(*count);
  for (int i = 0; i < *count; ++i) {
    const auto index = in.u8("sonar NUMBER");
    const auto range = in.u16("sonar RANGE");
    if (!range) {
      result.error = "standard SIP ends inside sonar reading " + std::to_string(i + 1) + " of " +
                     std::to_string(*count);
      return result;
    }
    if (*index >= kMaxSonars) {
      result.error = "sonar NUMBER " + std::to_string(*index) + " out of range 0-31";
      return result;
    }
    sip.sonars.push_back({*index, *range});
  }
  // Optional tail: each group only when complete.
  if (in.remaining() >= 5) {
    std::array<std::uint8_t, 5> io{};
    for (auto& b : io)
      b = *in.u8("IO");
    sip.io = io;
  }
  if (sip.io && in.remaining() >= 2)
    sip.battery_x10 = in.u16("BATTERYX10");
  if (sip.battery_x10 && in.remaining() >= 1)
    sip.charge_state = in.u8("CHARGESTATE");
  if (sip.charge_state && in.remaining() >= 2)
    sip.rotational_velocity = in.i16("ROTVEL");
  if (sip.rotational_velocity && in.remaining() >= 2)
    sip.fault_flags = in.u16("FAULTFLAGS");
  result.sip = std::move(sip);
  return result;
}

std::vector<std::uint8_t> encodeStandardSip(const StandardSip& sip) {
  if (sip.sonars.size() > kMaxSonars)
    throw std::invalid_argument("a standard SIP carries at most 32 sonar readings");
  std::vector<std::uint8_t> out;
  out.reserve(32 + 3 * sip.sonars.size());
  out.push_back(sip.type);
  put16(out, static_cast<std::uint16_t>(sip.x_raw & 0x7FFF));
  put16(out, static_cast<std::uint16_t>(sip.y_raw & 0x7FFF));
  put16(out, static_cast<std::uint16_t>(sip.theta_raw));
  put16(out, static_cast<std::uint16_t>(sip.left_velocity));
  put16(out, static_cast<std::uint16_t>(sip.right_velocity));
  out.push_back(sip.battery_decivolts);
  put16(out, sip.stall_and_bumpers);
  put16(out, static_cast<std::uint16_t>(sip.control));
  put16(out, sip.flags);
  out.push_back(sip.compass);
  out.push_back(static_cast<std::uint8_t>(sip.sonars.size()));
  for (const SonarRangeRaw& sonar : sip.sonars) {
    if (sonar.index >= kMaxSonars)
      throw std::invalid_argument("sonar index above 31");
    out.push_back(sonar.index);
    put16(out, sonar.range);
  }
  const bool any_tail =
      sip.io || sip.battery_x10 || sip.charge_state || sip.rotational_velocity || sip.fault_flags;
  if (!any_tail)
    return out;
  const std::array<std::uint8_t, 5> io = sip.io.value_or(std::array<std::uint8_t, 5>{});
  out.insert(out.end(), io.begin(), io.end());
  if (!(sip.battery_x10 || sip.charge_state || sip.rotational_velocity || sip.fault_flags))
    return out;
  put16(out, sip.battery_x10.value_or(0));
  if (!(sip.charge_state || sip.rotational_velocity || sip.fault_flags))
    return out;
  out.push_back(sip.charge_state.value_or(0));
  if (!(sip.rotational_velocity || sip.fault_flags))
    return out;
  put16(out, static_cast<std::uint16_t>(sip.rotational_velocity.value_or(0)));
  if (!sip.fault_flags)
    return out;
  put16(out, *sip.fault_flags);
  return out;
}

std::optional<RobotIdentity> parseSync2Reply(std::span<const std::uint8_t> payload) {
  if (payload.empty() || payload[0] != 2)
    return std::nullopt;
  RobotIdentity identity;
  std::string* fields[] = {&identity.name, &identity.robot_class, &identity.subclass};
  std::size_t field = 0;
  for (std::size_t i = 1; i < payload.size() && field < 3; ++i) {
    if (payload[i] == 0)
      ++field;
    else
      fields[field]->push_back(static_cast<char>(payload[i]));
  }
  // Some servers omit the last terminator; three non-empty-or-terminated fields are required.
  if (field < 2)
    return std::nullopt;
  return identity;
}

std::vector<std::uint8_t> encodeSync2Reply(const RobotIdentity& identity) {
  std::vector<std::uint8_t> out{2};
  for (const std::string* s : {&identity.name, &identity.robot_class, &identity.subclass}) {
    out.insert(out.end(), s->begin(), s->end());
    out.push_back(0);
  }
  return out;
}

std::int64_t OdometryUnwrapper::update(std::uint16_t raw) {
  constexpr int kRange = 1 << 15;
  raw = static_cast<std::uint16_t>(raw & 0x7FFF);
  if (last_) {
    int step = static_cast<int>(raw) - static_cast<int>(*last_);
    if (step > kRange / 2)
      step -= kRange;
    else if (step < -kRange / 2)
      step += kRange;
    total_ += step;
  }
  last_ = raw;
  return total_;
}

}  // namespace irgs::comms::arcos
