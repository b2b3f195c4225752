#pragma once
// Helpers of the recording tests: the QCoreApplication Qt Sql needs for its driver plugins, and
// temporary folders.

#include <QCoreApplication>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace irgs::recording::testing {

inline void ensureCoreApplication() {
  if (QCoreApplication::instance() != nullptr)
    return;
  static int argc = 1;
  static char name[] = "recording_test";
  static char* argv[] = {name, nullptr};
  static QCoreApplication app(argc, argv);
}

inline std::filesystem::path makeTempDir(const std::string& stem) {
  std::string pattern = (std::filesystem::temp_directory_path() / (stem + "-XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw std::runtime_error("mkdtemp failed");
  return pattern;
}

}  // namespace irgs::recording::testing
