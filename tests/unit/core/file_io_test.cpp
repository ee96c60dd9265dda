#include "common/core/file_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/scratch_dir.hpp"

namespace fleetmap {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class FileIoTest : public ::testing::Test {
 protected:
  std::string Path(const std::string& name) const { return dir_.Path(name); }
  std::vector<std::string> Listing() const { return dir_.Listing(); }

  testing::ScratchDir dir_{"file_io"};
};

TEST_F(FileIoTest, WritesAndReplacesContentsExactly) {
  const std::string path = Path("out.bin");
  const std::string with_nuls("a\0b\0\0c\n", 7);
  ASSERT_TRUE(WriteFileAtomically(path, with_nuls).ok());
  EXPECT_EQ(testing::ReadFile(path), with_nuls);

  ASSERT_TRUE(WriteFileAtomically(path, "shorter").ok());
  EXPECT_EQ(testing::ReadFile(path), "shorter");

  ASSERT_TRUE(WriteFileAtomically(path, "").ok());
  EXPECT_TRUE(fs::is_regular_file(path));
  EXPECT_EQ(fs::file_size(path), 0u);

  const std::vector<uint8_t> bytes = {0x89, 'P', 'N', 'G', 0, 255};
  ASSERT_TRUE(WriteFileAtomically(path, bytes).ok());
  EXPECT_EQ(testing::ReadFile(path), std::string(bytes.begin(), bytes.end()));
  EXPECT_EQ(Listing(), std::vector<std::string>{"out.bin"});
}

TEST_F(FileIoTest, NewFilesGetTheUmaskedMode) {
  const mode_t old_mask = umask(022);
  const Status status = WriteFileAtomically(Path("mode.txt"), "x");
  umask(old_mask);
  ASSERT_TRUE(status.ok()) << status;
  struct stat info;
  ASSERT_EQ(stat(Path("mode.txt").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0644u);
}

TEST_F(FileIoTest, MissingDirectoryIsUnavailableAndNamesThePath) {
  const std::string path = Path("no_such_dir") + "/x.vmap";
  const Status status = WriteFileAtomically(path, "bytes");
  EXPECT_EQ(status.code(), StatusCode::kUnavailable);
  EXPECT_EQ(status.message(), path + ": cannot write: No such file or directory");
  EXPECT_TRUE(Listing().empty());
}

// rename() cannot replace a non-empty directory: the temporary file was written and must go.
TEST_F(FileIoTest, FailedRenameLeavesTheTargetAndNoTemporaryFile) {
  const std::string target = Path("target");
  fs::create_directories(target);
  std::ofstream(target + "/inside.txt") << "keep";
  const Status status = WriteFileAtomically(target, "new contents");
  EXPECT_EQ(status.code(), StatusCode::kUnavailable);
  EXPECT_THAT(status.message(), HasSubstr(target + ": cannot write: "));
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_EQ(testing::ReadFile(target + "/inside.txt"), "keep");
  EXPECT_EQ(Listing(), std::vector<std::string>{"target"});
}

// A file size limit makes write() stop short, then fail with EFBIG; root is no exception, so
// this runs in CI (which runs as root, where permission tricks would not fail).
TEST_F(FileIoTest, FailedWriteLeavesTheOldFileUntouched) {
  const std::string path = Path("report.md");
  ASSERT_TRUE(WriteFileAtomically(path, "old report\n").ok());

  struct rlimit old_limit;
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old_limit), 0);
  struct rlimit small = old_limit;
  small.rlim_cur = 16;
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const Status status = WriteFileAtomically(path, std::string(1000, 'x'));
  setrlimit(RLIMIT_FSIZE, &old_limit);
  std::signal(SIGXFSZ, old_handler);

  EXPECT_EQ(status.code(), StatusCode::kUnavailable);
  EXPECT_EQ(status.message(), path + ": cannot write: File too large");
  EXPECT_EQ(testing::ReadFile(path), "old report\n");
  EXPECT_EQ(Listing(), std::vector<std::string>{"report.md"});
}

TEST_F(FileIoTest, WritesIntoDevNullWithoutReplacingIt) {
  ASSERT_TRUE(WriteFileAtomically("/dev/null", "discarded").ok());
  struct stat info;
  ASSERT_EQ(lstat("/dev/null", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
}

TEST_F(FileIoTest, WritesThroughASymbolicLink) {
  const std::string real = Path("real.txt");
  const std::string link = Path("link.txt");
  ASSERT_TRUE(WriteFileAtomically(real, "old").ok());
  fs::create_symlink(real, link);
  ASSERT_TRUE(WriteFileAtomically(link, "new").ok());
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(testing::ReadFile(real), "new");
}

}  // namespace
}  // namespace fleetmap
