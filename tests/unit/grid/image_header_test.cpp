#include "common/grid/image_header.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "tests/scratch_dir.hpp"
#include "tests/unit/grid/crafted_png.hpp"

namespace fleetmap::grid {
namespace {

using ::testing::HasSubstr;
using testing::PngChunk;
using testing::PngHead;
using ::testing::StartsWith;

std::string WriteFile(const fleetmap::testing::ScratchDir& dir, const std::string& name,
                      const std::string& bytes) {
  const std::string path = dir.Path(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(ImageHeaderTest, ReadsPngSizeAndTheLayoutOpenCvDecodesTo) {
  fleetmap::testing::ScratchDir dir("image_header");
  struct Case {
    int depth;
    int color_type;
    std::string more;
    int channels;
    int bytes_per_sample;
  };
  const std::string trns = PngChunk("tRNS", "\x01\x02");
  const std::string idat = PngChunk("IDAT", "x");
  const Case cases[] = {
      {8, 0, "", 1, 1},                              // gray
      {1, 0, "", 1, 1},                              // 1-bit gray is expanded to 8 bits
      {16, 0, trns, 1, 2},                           // gray: OpenCV drops the tRNS
      {8, 4, "", 4, 1},                              // gray + alpha becomes BGRA
      {8, 2, "", 3, 1},                              // RGB
      {8, 2, trns + idat, 4, 1},                     // RGB with a tRNS before the data gains alpha
      {8, 2, idat + trns, 3, 1},                     // ... not one after it
      {4, 3, PngChunk("PLTE", "abc") + trns, 4, 1},  // palette with transparency
      {16, 6, "", 4, 2},                             // RGBA16
  };
  for (const Case& c : cases) {
    const std::string path =
        WriteFile(dir, "h.png", PngHead(300, 200, c.depth, c.color_type, c.more));
    const StatusOr<ImageHeader> header = ReadImageHeader(path);
    ASSERT_TRUE(header.ok()) << header.status();
    EXPECT_EQ(header->format, "PNG");
    EXPECT_EQ(header->width, 300);
    EXPECT_EQ(header->height, 200);
    EXPECT_EQ(header->channels, c.channels) << c.color_type << "/" << c.depth;
    EXPECT_EQ(header->bytes_per_sample, c.bytes_per_sample) << c.color_type << "/" << c.depth;
  }
}

TEST(ImageHeaderTest, AgreesWithWhatOpenCvDecodes) {
  fleetmap::testing::ScratchDir dir("image_header");
  for (const int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_8UC4, CV_16UC3, CV_16UC4}) {
    for (const std::string extension : {".png", ".bmp"}) {
      if (extension == ".bmp" && CV_MAT_DEPTH(type) != CV_8U) continue;
      const std::string path = dir.Path("image" + extension);
      ASSERT_TRUE(cv::imwrite(path, cv::Mat(5, 7, type, cv::Scalar::all(100))));
      const StatusOr<ImageHeader> header = ReadImageHeader(path);
      ASSERT_TRUE(header.ok()) << header.status();
      const cv::Mat decoded = cv::imread(path, cv::IMREAD_UNCHANGED);
      EXPECT_EQ(header->width, decoded.cols);
      EXPECT_EQ(header->height, decoded.rows);
      // The header's count bounds the decoder's allocation: equal for PNG, at least for BMP.
      const int64_t header_bytes = int64_t{header->channels} * header->bytes_per_sample;
      if (extension == ".png") {
        EXPECT_EQ(header_bytes, static_cast<int64_t>(decoded.elemSize())) << type;
      } else {
        EXPECT_GE(header_bytes, static_cast<int64_t>(decoded.elemSize())) << type;
      }
    }
  }
}

std::string Le32(uint32_t value) {
  return {static_cast<char>(value), static_cast<char>(value >> 8), static_cast<char>(value >> 16),
          static_cast<char>(value >> 24)};
}

TEST(ImageHeaderTest, ReadsBmpSizeFromEitherHeaderAndCountsFourBytesPerPixel) {
  fleetmap::testing::ScratchDir dir("image_header");
  // File header (14 bytes: "BM", file size, reserved, pixel offset), then the DIB header.
  const std::string file_header = "BM" + std::string(12, '\0');
  // BITMAPINFOHEADER: size 40, width, height (negative: rows top-down).
  const std::string info = Le32(40) + Le32(60000) + Le32(static_cast<uint32_t>(-60000));
  StatusOr<ImageHeader> header = ReadImageHeader(WriteFile(dir, "a.bmp", file_header + info));
  ASSERT_TRUE(header.ok()) << header.status();
  EXPECT_EQ(header->format, "BMP");
  EXPECT_EQ(header->width, 60000);
  EXPECT_EQ(header->height, 60000);
  EXPECT_EQ(header->channels * header->bytes_per_sample, 4);
  EXPECT_EQ(header->CheckLimits("a.bmp", 400'000'000, int64_t{256} << 20).code(),
            StatusCode::kResourceExhausted);
  // OS/2 BITMAPCOREHEADER: size 12, 16-bit width and height, planes, bits per pixel.
  const std::string core = Le32(12) + std::string("\x10\x00\x20\x00\x01\x00\x18\x00", 8);
  header = ReadImageHeader(WriteFile(dir, "b.bmp", file_header + core));
  ASSERT_TRUE(header.ok()) << header.status();
  EXPECT_EQ(header->width, 16);
  EXPECT_EQ(header->height, 32);
}

TEST(ImageHeaderTest, RefusesWhatIsNotAHeaderItCanTrust) {
  fleetmap::testing::ScratchDir dir("image_header");
  struct Case {
    std::string bytes;
    StatusCode code;
    std::string message;
  };
  const std::string png = PngHead(10, 10, 8, 0);
  const Case cases[] = {
      {"", StatusCode::kDataLoss, "empty file"},
      {png.substr(0, 5), StatusCode::kDataLoss, "ends inside the PNG signature"},
      {png.substr(0, 20), StatusCode::kDataLoss, "ends inside the PNG header"},
      {std::string("\x89PNG\r\n\x1a\n", 8) + PngChunk("IDAT", std::string(13, 'x')),
       StatusCode::kInvalidArgument, "the first chunk is not a 13-byte IHDR"},
      {PngHead(0, 10, 8, 0), StatusCode::kInvalidArgument, "size 0 x 10"},
      {PngHead(0x80000000u, 10, 8, 0), StatusCode::kInvalidArgument, "size 2147483648 x 10"},
      {PngHead(10, 10, 16, 3), StatusCode::kInvalidArgument, "colour type 3 with bit depth 16"},
      {PngHead(10, 10, 8, 5), StatusCode::kInvalidArgument, "colour type 5"},
      {"BM" + std::string(10, '\0'), StatusCode::kDataLoss, "ends inside the BMP header"},
      {"GIF89a" + std::string(40, '\0'), StatusCode::kInvalidArgument, "not a PGM, PNG or BMP"},
  };
  for (const Case& c : cases) {
    const std::string path = WriteFile(dir, "bad.img", c.bytes);
    const StatusOr<ImageHeader> header = ReadImageHeader(path);
    ASSERT_FALSE(header.ok()) << c.message;
    EXPECT_EQ(header.status().code(), c.code) << header.status();
    EXPECT_THAT(header.status().message(), StartsWith(path + ": "));
    EXPECT_THAT(header.status().message(), HasSubstr(c.message));
  }
  EXPECT_EQ(ReadImageHeader(dir.Path("missing.png")).status().code(), StatusCode::kNotFound);
}

TEST(ImageHeaderTest, LimitsAreInclusiveAndNameTheFileTheSizeAndTheLimit) {
  const ImageHeader header{
      .format = "PNG", .width = 4, .height = 3, .channels = 4, .bytes_per_sample = 2};
  EXPECT_TRUE(header.CheckLimits("m.png", 12, 96).ok());

  const Status cells = header.CheckLimits("m.png", 11, 96);
  EXPECT_EQ(cells.code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(cells.message(), "m.png: image is 4 x 3 = 12 cells, more than the limit of 11");

  const Status bytes = header.CheckLimits("m.png", 12, 95);
  EXPECT_EQ(bytes.code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(bytes.message(),
            "m.png: image is 4 x 3 with 4 channel(s) of 16 bits, 96 bytes decoded, more than the "
            "limit of 95 bytes (max_decoded_bytes)");
}

TEST(ImageHeaderTest, LimitsNeverOverflow) {
  constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
  const ImageHeader largest{.format = "PNG",
                            .width = std::numeric_limits<int32_t>::max(),
                            .height = std::numeric_limits<int32_t>::max(),
                            .channels = 4,
                            .bytes_per_sample = 2};
  const Status status = largest.CheckLimits("m.png", kMax, kMax);
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(status.message(), HasSubstr("over 2^63 bytes decoded"));
}

}  // namespace
}  // namespace fleetmap::grid
