#pragma once
// Whole-file reads and crash-safe whole-file writes.
//
// writeFileAtomically never leaves the target half-written: the bytes go to a temporary file in
// the target's folder, which is flushed to disk (fsync) and then renamed over the target; the
// folder is synced afterwards so the rename itself survives a power cut. On any failure the
// temporary file is removed and the old target (if any) is untouched. POSIX only.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace irgs {

// Writes `bytes` to `path`, replacing it atomically. A symbolic link at `path` is followed (the
// link stays, its target is replaced). A new file gets mode 0644; an existing file keeps its
// permission bits. Returns nothing on success, otherwise a message naming the file and the
// failing step ("cannot create temporary file in /x: Permission denied").
std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view bytes);

struct ReadFileResult {
  std::string bytes;  // the whole file; empty on error
  std::string error;  // empty on success, otherwise a message naming the file

  bool ok() const { return error.empty(); }
};

// Reads a whole regular file. Fails (with a message) for missing files, folders and read errors.
ReadFileResult readFile(const std::filesystem::path& path);

}  // namespace irgs
