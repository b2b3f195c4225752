#include "core/io/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "tests/core/io/temp_dir.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;

std::size_t countEntries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
    ++n;
  return n;
}

TEST(AtomicFile, WritesANewFileAndReadsItBack) {
  test::TempDir dir;
  const fs::path file = dir / "a.bin";
  const std::string bytes("line 1\nbinary \0\xff\x01 end", 20);
  EXPECT_EQ(writeFileAtomically(file, bytes), std::nullopt);
  const ReadFileResult read = readFile(file);
  ASSERT_TRUE(read.ok()) << read.error;
  EXPECT_EQ(read.bytes, bytes);
  EXPECT_EQ(countEntries(dir.path()), 1U) << "no temporary file may stay behind";
}

TEST(AtomicFile, ReplacesAnExistingFileAndKeepsItsPermissions) {
  test::TempDir dir;
  const fs::path file = dir / "a.txt";
  ASSERT_EQ(writeFileAtomically(file, "old content that is longer"), std::nullopt);
  ASSERT_EQ(::chmod(file.c_str(), 0600), 0);
  ASSERT_EQ(writeFileAtomically(file, "new"), std::nullopt);
  EXPECT_EQ(readFile(file).bytes, "new");
  struct stat st {};
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600U);
}

TEST(AtomicFile, WritesAnEmptyFile) {
  test::TempDir dir;
  EXPECT_EQ(writeFileAtomically(dir / "empty", ""), std::nullopt);
  const ReadFileResult read = readFile(dir / "empty");
  EXPECT_TRUE(read.ok());
  EXPECT_TRUE(read.bytes.empty());
}

TEST(AtomicFile, FollowsASymbolicLinkAndKeepsTheLink) {
  test::TempDir dir;
  ASSERT_EQ(writeFileAtomically(dir / "real.txt", "one"), std::nullopt);
  fs::create_symlink("real.txt", dir / "link.txt");
  ASSERT_EQ(writeFileAtomically(dir / "link.txt", "two"), std::nullopt);
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(readFile(dir / "real.txt").bytes, "two");
}

TEST(AtomicFile, ReportsAMissingFolderAndLeavesNothingBehind) {
  test::TempDir dir;
  const auto error = writeFileAtomically(dir / "no-such-folder" / "a.txt", "x");
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("no-such-folder"), std::string::npos) << *error;
  EXPECT_EQ(countEntries(dir.path()), 0U);
}

TEST(AtomicFile, RefusesToReplaceAFolder) {
  test::TempDir dir;
  fs::create_directory(dir / "sub");
  const auto error = writeFileAtomically(dir / "sub", "x");
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("folder"), std::string::npos) << *error;
  EXPECT_TRUE(fs::is_directory(dir / "sub"));
  EXPECT_EQ(countEntries(dir.path()), 1U);
}

TEST(AtomicFile, FailureInAReadOnlyFolderKeepsTheOldContent) {
  if (::geteuid() == 0)
    GTEST_SKIP() << "running as root: folder permissions are not enforced";
  test::TempDir dir;
  const fs::path file = dir / "keep.txt";
  ASSERT_EQ(writeFileAtomically(file, "precious"), std::nullopt);
  ASSERT_EQ(::chmod(dir.path().c_str(), 0500), 0);
  const auto error = writeFileAtomically(file, "clobbered");
  ::chmod(dir.path().c_str(), 0700);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(readFile(file).bytes, "precious");
  EXPECT_EQ(countEntries(dir.path()), 1U);
}

TEST(AtomicFile, ReadingAMissingFileNamesIt) {
  test::TempDir dir;
  const ReadFileResult read = readFile(dir / "missing.json");
  EXPECT_FALSE(read.ok());
  EXPECT_NE(read.error.find("missing.json"), std::string::npos) << read.error;
  EXPECT_TRUE(read.bytes.empty());
}

TEST(AtomicFile, ReadingAFolderFails) {
  test::TempDir dir;
  const ReadFileResult read = readFile(dir.path());
  EXPECT_FALSE(read.ok());
  EXPECT_NE(read.error.find("folder"), std::string::npos) << read.error;
}

}  // namespace
}  // namespace irgs
