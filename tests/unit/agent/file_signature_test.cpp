#include "robot_agent/file_signature.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "tests/scratch_dir.hpp"

namespace fleetmap::agent {
namespace {

namespace fs = std::filesystem;

void Write(const std::string& path, const std::string& content) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << content;
}

TEST(FileSignatureTest, MissingFilesAreAllAlike) {
  testing::ScratchDir dir("file_signature");
  EXPECT_EQ(FileSignature::Of(dir.Path("missing")), FileSignature{});
  EXPECT_EQ(FileSignature::Of(""), FileSignature{});
  Write(dir.Path("a"), "abc");
  EXPECT_TRUE(FileSignature::Of(dir.Path("a")).exists);
  EXPECT_EQ(FileSignature::Of(dir.Path("a")).size, 3);
  EXPECT_NE(FileSignature::Of(dir.Path("a")), FileSignature{});
}

TEST(FileSignatureTest, SeesRewritesInPlaceAndByRename) {
  testing::ScratchDir dir("file_signature");
  const std::string path = dir.Path("map.pgm");
  Write(path, "first");
  const auto written = fs::last_write_time(path);
  const FileSignature first = FileSignature::Of(path);
  EXPECT_EQ(FileSignature::Of(path), first);  // reading it changes nothing

  // Same size, modification time set forward: in place.
  Write(path, "other");
  fs::last_write_time(path, written + std::chrono::seconds(1));
  const FileSignature in_place = FileSignature::Of(path);
  EXPECT_NE(in_place, first);
  EXPECT_EQ(in_place.inode, first.inode);
  EXPECT_EQ(in_place.size, first.size);

  // Same size and modification time as before, but another file renamed over it.
  const std::string temp = dir.Path("map.pgm.tmp");
  Write(temp, "third");
  fs::last_write_time(temp, written + std::chrono::seconds(1));
  fs::rename(temp, path);
  const FileSignature renamed = FileSignature::Of(path);
  EXPECT_NE(renamed, in_place);
  EXPECT_NE(renamed.inode, in_place.inode);
  EXPECT_EQ(renamed.mtime_ns, in_place.mtime_ns);
  EXPECT_EQ(renamed.size, in_place.size);
}

}  // namespace
}  // namespace fleetmap::agent
