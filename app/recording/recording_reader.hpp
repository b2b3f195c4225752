#pragma once
// Reads a whole session recording (recording_format.hpp) into memory. Also reads a file whose
// writer was killed (SQLite rolls the WAL forward on open) and a file still being written.
// Problems are values: a file that is not a recording is an error; unusable rows (non-finite
// times, unknown directions, empty frames) are skipped and counted in the warnings.
//
// Qt Sql needs a QCoreApplication (driver plugins).

#include "app/recording/recording_format.hpp"

#include <optional>
#include <string>
#include <vector>

namespace irgs::recording {

struct LoadResult {
  std::optional<Recording> recording;  // empty when error is set
  std::string error;
  std::vector<std::string> warnings;
};

LoadResult loadRecording(const std::string& path);

}  // namespace irgs::recording
