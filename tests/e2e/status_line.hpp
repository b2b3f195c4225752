#pragma once
// The GUI's machine-readable status lines in end-to-end tests: `irgs --status-interval` prints
// "status key=value key=value ..."; these read them from a child process.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include "child_process.hpp"

namespace irgs::test {

using Fields = std::map<std::string, std::string>;

// The fields of a status line; empty for any other line.
inline Fields parseStatus(const std::string& line) {
  Fields fields;
  if (line.rfind("status ", 0) != 0)
    return fields;
  std::istringstream in(line.substr(7));
  std::string word;
  while (in >> word) {
    const auto eq = word.find('=');
    if (eq != std::string::npos)
      fields[word.substr(0, eq)] = word.substr(eq + 1);
  }
  return fields;
}

// A field as a number; 0 when absent.
inline double number(const Fields& fields, const std::string& key) {
  const auto it = fields.find(key);
  return it == fields.end() ? 0.0 : std::strtod(it->second.c_str(), nullptr);
}

// Reads status lines until `done` accepts one (returned) or `timeout_s` passes (a test failure
// naming `what`, and an empty result).
inline Fields waitStatus(ChildProcess& gui, const std::function<bool(const Fields&)>& done,
                         double timeout_s, const std::string& what) {
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
  while (auto line = gui.readLine(deadline)) {
    Fields fields = parseStatus(*line);
    if (!fields.empty() && done(fields))
      return fields;
  }
  ADD_FAILURE() << "timed out after " << timeout_s << " s waiting for " << what;
  return {};
}

// Reads until the child closes its stdout (it has exited), at most `timeout_s`.
inline bool waitExit(ChildProcess& child, double timeout_s) {
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
  while (child.readLine(deadline)) {
  }
  return Clock::now() < deadline;
}

}  // namespace irgs::test
