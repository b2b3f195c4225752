// The ground side of the parameter protocol without a link: what it sends, how it retries
// missing indices and unanswered writes, and how it judges the robot's answer.

#include "comms/robot/param_client.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace irgs::comms {
namespace {

namespace mav = mavlink;

mav::ParamValue value(const char* name, float v, int index, int count) {
  mav::ParamValue m;
  std::memcpy(m.param_id.data(), name, std::strlen(name));
  m.param_value = v;
  m.param_type = static_cast<std::uint8_t>(mav::MavParamType::kReal32);
  m.param_index = static_cast<std::uint16_t>(index);
  m.param_count = static_cast<std::uint16_t>(count);
  return m;
}

TEST(ParamClient, ReadAllAsksForMissingIndicesOneByOne) {
  ParamClient client(7);
  client.requestAll(0.0);
  auto out = client.takeOutgoing();
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<mav::ParamRequestList>(out[0]));
  EXPECT_EQ(std::get<mav::ParamRequestList>(out[0]).target_system, 7);
  client.onParamValue(value("A", 1.0F, 0, 3), 0.1);
  client.onParamValue(value("C", 3.0F, 2, 3), 0.2);
  EXPECT_TRUE(client.reading());
  EXPECT_FALSE(client.complete());
  client.tick(0.3);  // not yet kRetry_s after the last value
  EXPECT_TRUE(client.takeOutgoing().empty());
  client.tick(0.2 + ParamClient::kRetry_s + 0.01);
  out = client.takeOutgoing();
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<mav::ParamRequestRead>(out[0]));
  EXPECT_EQ(std::get<mav::ParamRequestRead>(out[0]).param_index, 1);
  client.onParamValue(value("B", 2.0F, 1, 3), 0.8);
  EXPECT_TRUE(client.complete());
  EXPECT_FALSE(client.reading());
  const auto params = client.params();
  ASSERT_EQ(params.size(), 3u);
  EXPECT_EQ(params[1].name, "B");
  EXPECT_DOUBLE_EQ(params[2].value, 3.0);
}

TEST(ParamClient, AWriteIsAcceptedRejectedOrTimesOut) {
  ParamClient client(1);
  client.set("MAX_SPEED", 0.25, 0.0);
  auto out = client.takeOutgoing();
  ASSERT_EQ(out.size(), 1u);
  const auto& set = std::get<mav::ParamSet>(out[0]);
  EXPECT_FLOAT_EQ(set.param_value, 0.25F);
  EXPECT_EQ(set.param_type, static_cast<std::uint8_t>(mav::MavParamType::kReal32));
  client.onParamValue(value("MAX_SPEED", 0.25F, 2, 9), 0.1);
  auto results = client.takeResults();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].status, ParamWriteStatus::kAccepted);

  client.set("TELEOP_TIMEOUT", 1.0, 1.0);
  client.onParamValue(value("TELEOP_TIMEOUT", 0.3F, 0, 9), 1.1);  // robot kept its value
  results = client.takeResults();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].status, ParamWriteStatus::kRejected);
  EXPECT_NEAR(*results[0].applied, 0.3, 1e-6);

  client.set("HB_TIMEOUT", 2.0, 2.0);
  client.takeOutgoing();
  int resends = 0;
  for (double t = 2.0; t < 10.0; t += 0.1) {
    client.tick(t);
    resends += static_cast<int>(client.takeOutgoing().size());
  }
  EXPECT_EQ(resends, ParamClient::kMaxRetries);
  results = client.takeResults();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].status, ParamWriteStatus::kTimedOut);
  EXPECT_FALSE(client.writing());
  EXPECT_THROW(client.set("X", std::nan(""), 0.0), std::invalid_argument);
  EXPECT_THROW(client.set("", 1.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
