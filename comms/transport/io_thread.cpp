#include "comms/transport/io_thread.hpp"

namespace irgs::comms {

IoThread::IoThread() : work_(boost::asio::make_work_guard(io_)) {
  thread_ = std::thread([this] {
    // A handler that throws (a user callback, typically) must not take every link down with it:
    // count it and keep running.
    for (;;) {
      try {
        io_.run();
        break;
      } catch (...) {
        escaped_exceptions_.fetch_add(1);
      }
    }
    running_.store(false);
  });
}

IoThread::~IoThread() {
  running_.store(false);
  work_.reset();
  io_.stop();
  if (thread_.joinable())
    thread_.join();
}

}  // namespace irgs::comms
