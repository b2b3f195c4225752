#include "comms/transport/io_thread.hpp"

#include <gtest/gtest.h>
#include <boost/asio/post.hpp>

#include <chrono>
#include <future>
#include <stdexcept>

namespace irgs::comms {
namespace {

TEST(IoThread, RunsPostedWorkOnItsOwnThread) {
  IoThread io;
  std::promise<bool> on_io_thread;
  boost::asio::post(io.context(), [&] { on_io_thread.set_value(io.isCurrentThread()); });
  auto result = on_io_thread.get_future();
  ASSERT_EQ(result.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_TRUE(result.get());
  EXPECT_FALSE(io.isCurrentThread());
}

TEST(IoThread, SurvivesAHandlerThatThrowsAndCountsIt) {
  IoThread io;
  boost::asio::post(io.context(), [] { throw std::runtime_error("callback bug"); });
  std::promise<void> later;
  boost::asio::post(io.context(), [&] { later.set_value(); });
  ASSERT_EQ(later.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_EQ(io.escapedExceptions(), 1u);
  EXPECT_TRUE(io.running());
}

}  // namespace
}  // namespace irgs::comms
