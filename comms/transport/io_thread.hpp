#pragma once
// One io_context and the one thread that runs it, shared by every link (libmavconn used a thread
// per connection; a ground station with a handful of links needs only one).

#include <utility>  // Boost 1.74 Asio under C++20 needs this before any Asio header.

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>

#include <atomic>
#include <cstdint>
#include <thread>

namespace irgs::comms {

class IoThread {
 public:
  // Starts the thread; it idles until work is posted.
  IoThread();
  // Stops the io_context and joins the thread. Destroy every transport created on it first.
  ~IoThread();
  IoThread(const IoThread&) = delete;
  IoThread& operator=(const IoThread&) = delete;

  boost::asio::io_context& context() { return io_; }
  bool isCurrentThread() const { return std::this_thread::get_id() == thread_.get_id(); }
  // False once the destructor has started (or the loop ended).
  bool running() const { return running_.load(); }
  // Exceptions that escaped a handler (e.g. thrown by a user callback). The loop survives them.
  std::uint64_t escapedExceptions() const { return escaped_exceptions_.load(); }

 private:
  boost::asio::io_context io_;
  boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_;
  std::atomic<bool> running_{true};
  std::atomic<std::uint64_t> escaped_exceptions_{0};
  std::thread thread_;
};

}  // namespace irgs::comms
