// Child of recording_kill_test: records a known frame stream (frame i = pattern(i), one every
// 2 ms) into argv[1] until it is killed, printing "frame I T" (index, recorder time) after each
// frame was queued, so the parent knows what the recorder had been given when it killed it.

#include "app/recording/session_recorder.hpp"

#include <QCoreApplication>

#include <chrono>
#include <cstdio>
#include <thread>

#include "tests/app/recording/recording_pattern.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: recording_kill_child FILE\n");
    return 2;
  }
  QCoreApplication app(argc, argv);
  auto opened = irgs::recording::SessionRecorder::create(argv[1], {{"program", "kill test"}});
  if (!opened.recorder) {
    std::fprintf(stderr, "%s\n", opened.error.c_str());
    return 1;
  }
  std::printf("ready\n");
  std::fflush(stdout);
  for (std::size_t i = 0;; ++i) {
    const auto now = std::chrono::steady_clock::now();
    opened.recorder->recordFrame(irgs::comms::TapDirection::kReceived, now,
                                 irgs::recording::testing::pattern(i));
    std::printf("frame %zu %.6f\n", i, opened.recorder->now_s());
    std::fflush(stdout);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}
