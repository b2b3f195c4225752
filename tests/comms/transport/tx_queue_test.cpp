#include "comms/transport/tx_queue.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace irgs::comms {
namespace {

std::vector<std::uint8_t> bytesOf(std::size_t n, std::uint8_t value) {
  return std::vector<std::uint8_t>(n, value);
}

TEST(TxQueue, RefusesAChunkThatWouldExceedTheBound) {
  TxQueue q(10);
  EXPECT_TRUE(q.push(bytesOf(6, 1)));
  EXPECT_FALSE(q.push(bytesOf(5, 2)));
  EXPECT_TRUE(q.push(bytesOf(4, 3)));
  EXPECT_EQ(q.bytes(), 10u);
  EXPECT_FALSE(q.push(bytesOf(1, 4)));
  EXPECT_FALSE(TxQueue(3).push(bytesOf(4, 1)));
}

TEST(TxQueue, PopsInFifoOrderAndCountsInFlightBytesUntilReleased) {
  TxQueue q(100);
  ASSERT_TRUE(q.push(bytesOf(3, 7)));
  ASSERT_TRUE(q.push(bytesOf(2, 9)));
  const auto first = q.pop();
  ASSERT_TRUE(first);
  EXPECT_EQ(*first, bytesOf(3, 7));
  EXPECT_EQ(q.bytes(), 5u);  // in flight still counts against the bound
  q.release(first->size());
  EXPECT_EQ(q.bytes(), 2u);
  const auto second = q.pop();
  ASSERT_TRUE(second);
  EXPECT_EQ(*second, bytesOf(2, 9));
  EXPECT_FALSE(q.pop());
}

TEST(TxQueue, ClearReportsTheWaitingBytesItDropped) {
  TxQueue q(100);
  ASSERT_TRUE(q.push(bytesOf(3, 1)));
  ASSERT_TRUE(q.push(bytesOf(4, 1)));
  ASSERT_TRUE(q.pop());
  EXPECT_EQ(q.clear(), 4u);
  EXPECT_EQ(q.bytes(), 0u);
  EXPECT_TRUE(q.empty());
}

TEST(TxQueue, AcceptsEmptyChunksWithoutQueueingThem) {
  TxQueue q(1);
  EXPECT_TRUE(q.push({}));
  EXPECT_TRUE(q.empty());
}

}  // namespace
}  // namespace irgs::comms
