#include "common/extrapolation/ply_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

namespace fleetmap::extrapolation {
namespace {

using ::testing::HasSubstr;

TEST(PlyReaderTest, ReadsAscii) {
  const std::string text =
      "ply\nformat ascii 1.0\ncomment hi\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 0\nproperty list uchar int "
      "vertex_indices\n"
      "end_header\n1 2 3 255\n-1.5 0 2e-1 0\n";
  const auto cloud = ParsePly(text, "a.ply");
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ASSERT_EQ(cloud->size(), 2u);
  EXPECT_TRUE((*cloud)[1].isApprox(Point3(-1.5, 0, 0.2)));
}

TEST(PlyReaderTest, ReadsBinaryLittleEndianDoublesWithOtherProperties) {
  std::string bytes =
      "ply\r\nformat binary_little_endian 1.0\r\nelement vertex 2\r\nproperty uchar flag\r\n"
      "property double x\r\nproperty double y\r\nproperty double z\r\nend_header\r\n";
  for (double v : {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}) {
    if (v == 1.0 || v == 4.0) bytes.push_back('\x07');
    char raw[8];
    std::memcpy(raw, &v, 8);
    bytes.append(raw, 8);
  }
  const auto cloud = ParsePly(bytes, "b.ply");
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ASSERT_EQ(cloud->size(), 2u);
  EXPECT_TRUE((*cloud)[0].isApprox(Point3(1, 2, 3)));
  EXPECT_TRUE((*cloud)[1].isApprox(Point3(4, 5, 6)));
}

TEST(PlyReaderTest, WriteThenRead) {
  const std::string path = ::testing::TempDir() + "/ply_reader_test.ply";
  const PointCloud cloud = {Point3(1, 2, 3), Point3(-0.5, 0.25, 8)};
  for (bool ascii : {false, true}) {
    ASSERT_TRUE(WritePly(cloud, path, ascii).ok());
    const auto back = ReadPly(path);
    ASSERT_TRUE(back.ok()) << back.status();
    ASSERT_EQ(back->size(), 2u);
    EXPECT_TRUE((*back)[1].isApprox(cloud[1]));
  }
  std::filesystem::remove(path);
}

TEST(PlyReaderTest, EmptyCloudIsNotAnError) {
  const auto cloud = ParsePly(
      "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n",
      "empty.ply");
  ASSERT_TRUE(cloud.ok());
  EXPECT_TRUE(cloud->empty());
}

void ExpectError(const std::string& bytes, const std::string& what,
                 StatusCode code = StatusCode::kInvalidArgument) {
  const auto cloud = ParsePly(bytes, "bad.ply", 1000);
  ASSERT_FALSE(cloud.ok()) << what;
  EXPECT_EQ(cloud.status().code(), code) << cloud.status();
  EXPECT_THAT(cloud.status().message(), HasSubstr("bad.ply"));
  EXPECT_THAT(cloud.status().message(), HasSubstr(what));
}

TEST(PlyReaderTest, BadFilesAreErrorsNamingTheFile) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  ExpectError("PK\x03\x04", "not a PLY file");
  ExpectError("ply\nformat binary_big_endian 1.0\nelement vertex 1\n" + xyz + "end_header\n",
              "big_endian");
  ExpectError(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "end_header\n1 2\n",
      "no 'z' property");
  ExpectError(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n",
      "not float or double");
  ExpectError("ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + "end_header\n1 2 3\n",
              "truncated");
  ExpectError("ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz + "end_header\nabc",
              "truncated");
  ExpectError("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "end_header\n1 nan 3\n",
              "not finite");
  ExpectError("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "end_header\n1 x 3\n",
              "not a number");
  ExpectError("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz, "no 'end_header'");
  ExpectError("ply\nformat ascii 1.0\nelement vertex 5000\n" + xyz + "end_header\n",
              "more than the limit", StatusCode::kResourceExhausted);
}

TEST(PlyReaderTest, MissingFileIsNotFound) {
  const auto cloud = ReadPly("/nonexistent/cloud.ply");
  ASSERT_FALSE(cloud.ok());
  EXPECT_EQ(cloud.status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace fleetmap::extrapolation
