#include "core/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace irgs {
namespace {

std::string errnoText(int err) {
  return std::error_code(err, std::generic_category()).message();
}

// Closes a descriptor once; keeps error paths short.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() { close(); }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;

  int get() const { return fd_; }
  // Returns 0 or the errno of a failed close (a failed close can mean lost data on NFS).
  int close() {
    if (fd_ < 0)
      return 0;
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc == 0 ? 0 : errno;
  }

 private:
  int fd_;
};

bool writeAll(int fd, std::string_view bytes, int& err) {
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR)
        continue;
      err = errno;
      return false;
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

// Syncs a folder so a rename inside it is durable. Some file systems refuse fsync on folders
// (EINVAL); the data itself is already on disk then, so that is not treated as a failure.
std::optional<std::string> syncDirectory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0)
    return "cannot open folder " + dir.string() + " to sync it: " + errnoText(errno);
  FileDescriptor guard(fd);
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS)
    return "cannot sync folder " + dir.string() + ": " + errnoText(errno);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view bytes) {
  if (path.empty())
    return std::string("cannot write a file with an empty path");
  std::error_code ec;
  std::filesystem::path target = path;
  // Follow a symbolic link so the link survives and its target gets the new content.
  if (std::filesystem::is_symlink(target, ec)) {
    const std::filesystem::path resolved = std::filesystem::read_symlink(target, ec);
    if (!ec)
      target = resolved.is_absolute() ? resolved : target.parent_path() / resolved;
  }
  if (std::filesystem::is_directory(target, ec))
    return "cannot write " + path.string() + ": it is a folder";

  std::filesystem::path dir = target.parent_path();
  if (dir.empty())
    dir = ".";
  mode_t mode = 0644;
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0)
    mode = st.st_mode & 07777;

  std::string temp = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0)
    return "cannot create a temporary file in " + dir.string() + ": " + errnoText(errno);
  FileDescriptor file(fd);
  auto fail = [&](const std::string& what, int err) -> std::optional<std::string> {
    file.close();
    ::unlink(temp.c_str());
    return what + ": " + errnoText(err);
  };

  int err = 0;
  if (!writeAll(fd, bytes, err))
    return fail("cannot write " + temp, err);
  if (::fchmod(fd, mode) != 0)
    return fail("cannot set permissions of " + temp, errno);
  if (::fsync(fd) != 0)
    return fail("cannot flush " + temp + " to disk", errno);
  if (const int close_err = file.close(); close_err != 0)
    return fail("cannot close " + temp, close_err);
  if (::rename(temp.c_str(), target.c_str()) != 0)
    return fail("cannot replace " + target.string(), errno);
  return syncDirectory(dir);
}

ReadFileResult readFile(const std::filesystem::path& path) {
  ReadFileResult result;
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    result.error = "cannot open " + path.string() + ": no such file";
    return result;
  }
  if (std::filesystem::is_directory(status)) {
    result.error = "cannot read " + path.string() + ": it is a folder";
    return result;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    result.error = "cannot open " + path.string() + ": " + errnoText(errno);
    return result;
  }
  std::string bytes;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    bytes.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) {
    result.error = "cannot read " + path.string() + ": read error";
    return result;
  }
  result.bytes = std::move(bytes);
  return result;
}

}  // namespace irgs
