#pragma once
// Test helper for the irgs-sim end-to-end tests: a child process (irgs-robot, irgs-sim) with its
// stdout and stderr on one pipe, waited for with deadlines, killed and reaped on destruction.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace irgs::test {

using Clock = std::chrono::steady_clock;

inline double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A child process with stdout and stderr on one pipe; killed and reaped on destruction.
class Child {
 public:
  explicit Child(const std::vector<std::string>& args) {
    int out[2];
    if (::pipe(out) != 0)
      return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      ::dup2(out[1], STDERR_FILENO);
      ::close(out[0]);
      ::close(out[1]);
      std::vector<char*> argv;
      for (const auto& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    out_ = out[0];
    ::fcntl(out_, F_SETFL, ::fcntl(out_, F_GETFL) | O_NONBLOCK);
  }
  ~Child() {
    if (pid_ > 0 && !status_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_ >= 0)
      ::close(out_);
  }
  bool started() const { return pid_ > 0; }

  // Reads what is available (waiting up to `timeout_s` for something).
  void pump(double timeout_s) {
    pollfd p{out_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout_s * 1000)) <= 0)
      return;
    char buf[4096];
    for (;;) {
      const ssize_t n = ::read(out_, buf, sizeof buf);
      if (n <= 0)
        break;
      output_.append(buf, static_cast<std::size_t>(n));
    }
  }
  // Waits until the output contains `text`.
  bool waitOutput(const std::string& text, double timeout_s) {
    const auto t0 = Clock::now();
    while (output_.find(text) == std::string::npos) {
      if (since(t0) > timeout_s || exited())
        return output_.find(text) != std::string::npos;
      pump(0.05);
    }
    return true;
  }
  bool exited() {
    if (status_)
      return true;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_)
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return status_.has_value();
  }
  // Waits up to `timeout_s` for the exit (collecting output); the exit status or -1.
  int wait(double timeout_s) {
    const auto t0 = Clock::now();
    while (!exited()) {
      if (since(t0) > timeout_s)
        return -1;
      pump(0.05);
    }
    pump(0.0);
    return *status_;
  }
  void signal(int sig) { ::kill(pid_, sig); }
  const std::string& output() const { return output_; }

 private:
  pid_t pid_ = -1;
  int out_ = -1;
  std::string output_;
  std::optional<int> status_;
};

}  // namespace irgs::test
