#include "common/grid/pgm.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace fleetmap::grid {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string DataPath(const std::string& name) {
  return std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/" + name;
}

StatusOr<PgmImage> Decode(const std::string& bytes, const PgmReadOptions& options = {}) {
  return DecodePgm(bytes, "mem.pgm", options);
}

TEST(PgmTest, ReadsAsciiWithCommentsAnywhereInTheHeader) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("trinary_4x3.pgm"));
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->width, 4);
  EXPECT_EQ(image->height, 3);
  EXPECT_EQ(image->max_value, 255);
  EXPECT_EQ(image->pixels,
            (std::vector<uint16_t>{0, 89, 90, 255, 204, 205, 254, 100, 206, 50, 230, 1}));
  EXPECT_EQ(image->at(3, 0), 255);
  EXPECT_EQ(image->at(0, 2), 206);
}

TEST(PgmTest, ReadsBinary8Bit) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("raw_4x3.pgm"));
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->pixels,
            (std::vector<uint16_t>{0, 1, 50, 100, 101, 200, 255, 99, 37, 3, 100, 0}));
}

TEST(PgmTest, ReadsBinary16BitBigEndian) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("p5_16bit.pgm"));
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->max_value, 65535);
  EXPECT_EQ(image->pixels, (std::vector<uint16_t>{0x0102, 0xff00, 0xffff, 0}));
}

TEST(PgmTest, ReadsAscii16Bit) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("p2_16bit.pgm"));
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->width, 3);
  EXPECT_EQ(image->height, 2);
  EXPECT_EQ(image->pixels, (std::vector<uint16_t>{0, 65535, 32768, 65000, 12850, 52700}));
}

TEST(PgmTest, TwoByteSamplesStartAboveMaxval255) {
  // maxval 256 already needs two bytes per sample.
  const std::string bytes = std::string("P5\n2 1\n256\n") + '\x01' + '\x00' + '\x00' + '\x07';
  const StatusOr<PgmImage> image = Decode(bytes);
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->pixels, (std::vector<uint16_t>{256, 7}));
}

TEST(PgmTest, CommentMayEndTheHeader) {
  const std::string bytes = std::string("P5 2 1 255#comment\n") + '\x05' + '\x06';
  const StatusOr<PgmImage> image = Decode(bytes);
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->pixels, (std::vector<uint16_t>{5, 6}));
}

TEST(PgmTest, MissingFileIsNotFound) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("nope.pgm"));
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(image.status().message(), HasSubstr("nope.pgm: no such file"));
}

TEST(PgmTest, RejectsWrongMagic) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("bad_magic.pgm"));
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(image.status().message(), StartsWith(DataPath("bad_magic.pgm") + ": "));
  EXPECT_THAT(image.status().message(), HasSubstr("expected magic 'P5' or 'P2', found 'Q' '5'"));

  const StatusOr<PgmImage> color = Decode("P6\n1 1\n255\n\x01\x02\x03");
  ASSERT_FALSE(color.ok());
  EXPECT_THAT(color.status().message(), HasSubstr("unsupported Netpbm type P6"));
  EXPECT_FALSE(Decode("P55 1 1 255 \x01").ok());
  EXPECT_EQ(Decode("").status().code(), StatusCode::kDataLoss);
}

TEST(PgmTest, RejectsTruncatedBinaryPixels) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("truncated.pgm"));
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kDataLoss);
  EXPECT_EQ(
      image.status().message(),
      DataPath("truncated.pgm") + ": truncated: expected 12 bytes of pixels (4 x 3 x 1), found 5");
  // 16 bit: an odd byte at the end is not a sample.
  const StatusOr<PgmImage> wide = Decode(std::string("P5 2 1 65535\n") + '\x01' + '\x02' + '\x03');
  ASSERT_FALSE(wide.ok());
  EXPECT_THAT(wide.status().message(),
              HasSubstr("expected 4 bytes of pixels (2 x 1 x 2), found 3"));
}

TEST(PgmTest, RejectsAsciiSizeMismatch) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("size_mismatch.pgm"));
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kDataLoss);
  EXPECT_EQ(image.status().message(),
            DataPath("size_mismatch.pgm") + ": truncated: expected 12 pixel values, found 10");
  const StatusOr<PgmImage> extra = Decode("P2 2 1 255 1 2 3\n");
  ASSERT_FALSE(extra.ok());
  EXPECT_THAT(extra.status().message(), HasSubstr("unexpected data after the pixels"));
}

TEST(PgmTest, RejectsTruncatedHeader) {
  for (const std::string bytes : {"P5", "P5\n", "P5 4", "P5 4 3", "P5 4 3 255", "P2 # only"}) {
    const StatusOr<PgmImage> image = Decode(bytes);
    ASSERT_FALSE(image.ok()) << bytes;
    EXPECT_EQ(image.status().code(), StatusCode::kDataLoss) << bytes;
    EXPECT_THAT(image.status().message(), StartsWith("mem.pgm: ")) << bytes;
  }
}

TEST(PgmTest, RejectsBadHeaderFields) {
  struct Case {
    std::string bytes;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"P5 0 3 255 ", "bad width: 0 is below the minimum of 1"},
      {"P5 4 0 255 ", "bad height: 0 is below the minimum of 1"},
      {"P5 -4 3 255 ", "bad width: expected a positive decimal number, found '-'"},
      {"P5 4 -3 255 ", "bad height: expected a positive decimal number, found '-'"},
      {"P5 4 3 0 ", "bad maxval: 0 is below the minimum of 1"},
      {"P5 4 3 65536 ", "bad maxval: 65536 is above the maximum of 65535"},
      {"P5 4 3 -1 ", "bad maxval: expected a positive decimal number, found '-'"},
      {"P5 2147483648 1 255 ", "bad width: 2147483648 is above the maximum of 2147483647"},
      {"P5 99999999999999999999999 1 255 ", "is above the maximum of 2147483647"},
      {"P5 4x 3 255 ", "bad width: '4' is followed by 'x'"},
      {"P5 4 3 255x", "bad maxval: '255' is followed by 'x'"},
      {"P5 4.5 3 255 ", "bad width: '4' is followed by '.'"},
  };
  for (const Case& c : cases) {
    const StatusOr<PgmImage> image = Decode(c.bytes);
    ASSERT_FALSE(image.ok()) << c.bytes;
    EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument) << c.bytes;
    EXPECT_THAT(image.status().message(), HasSubstr(c.message)) << c.bytes;
  }
}

TEST(PgmTest, RejectsAbsurdSizeBeforeAllocating) {
  const StatusOr<PgmImage> image = ReadPgm(DataPath("absurd_size.pgm"));
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(image.status().message(),
            DataPath("absurd_size.pgm") +
                ": image is 100000 x 100000 = 10000000000 cells, more than the limit of 400000000");
  // The largest header int32 allows cannot overflow the cell count either.
  const StatusOr<PgmImage> huge = Decode("P5 2147483647 2147483647 65535 ");
  EXPECT_EQ(huge.status().code(), StatusCode::kResourceExhausted);
}

TEST(PgmTest, MaxCellsIsAnInclusiveLimit) {
  PgmReadOptions options;
  options.max_cells = 12;
  EXPECT_TRUE(ReadPgm(DataPath("raw_4x3.pgm"), options).ok());
  options.max_cells = 11;
  EXPECT_EQ(ReadPgm(DataPath("raw_4x3.pgm"), options).status().code(),
            StatusCode::kResourceExhausted);
}

TEST(PgmTest, MaxDecodedBytesCountsSixteenBitsPerSample) {
  PgmReadOptions options;
  options.max_decoded_bytes = 24;  // 4 x 3 samples of 2 bytes
  EXPECT_TRUE(ReadPgm(DataPath("raw_4x3.pgm"), options).ok());
  options.max_decoded_bytes = 23;
  const StatusOr<PgmImage> image = ReadPgm(DataPath("raw_4x3.pgm"), options);
  EXPECT_EQ(image.status().code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(image.status().message(),
            DataPath("raw_4x3.pgm") +
                ": image is 4 x 3 with 1 channel(s) of 16 bits, 24 bytes decoded, more than the "
                "limit of 23 bytes (max_decoded_bytes)");
  // The default limit, 256 MiB, holds 134217728 samples.
  EXPECT_EQ(Decode("P5 16384 8192 255 ").status().code(), StatusCode::kDataLoss);
  EXPECT_EQ(Decode("P5 16384 8193 255 ").status().code(), StatusCode::kResourceExhausted);
}

TEST(PgmTest, HoldsExactlyTheSamplesOfTheImage) {
  // More samples than the first reservation: the buffer grows, but never past width * height.
  PgmImage image;
  image.width = 1500;
  image.height = 1000;
  image.pixels.assign(1'500'000, 7);
  for (const PgmEncoding encoding : {PgmEncoding::kBinary, PgmEncoding::kAscii}) {
    const StatusOr<std::string> bytes = EncodePgm(image, encoding);
    ASSERT_TRUE(bytes.ok()) << bytes.status();
    const StatusOr<PgmImage> read = Decode(*bytes);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_EQ(read->pixels, image.pixels);
    EXPECT_EQ(read->pixels.capacity(), image.pixels.size());
  }
}

TEST(PgmTest, RejectsPixelAboveMaxval) {
  const StatusOr<PgmImage> ascii = Decode("P2 2 2 100 50 0 7 101\n");
  ASSERT_FALSE(ascii.ok());
  EXPECT_EQ(ascii.status().code(), StatusCode::kDataLoss);
  EXPECT_EQ(ascii.status().message(), "mem.pgm: pixel (1, 1) is 101, above maxval 100");
  const StatusOr<PgmImage> binary = Decode(std::string("P5 2 1 100\n") + '\x05' + '\xc8');
  ASSERT_FALSE(binary.ok());
  EXPECT_EQ(binary.status().message(), "mem.pgm: pixel (1, 0) is 200, above maxval 100");
  const StatusOr<PgmImage> big = Decode("P2 1 1 65535 99999999\n");
  ASSERT_FALSE(big.ok());
  EXPECT_THAT(big.status().message(), HasSubstr("is > 65535, above maxval 65535"));
  const StatusOr<PgmImage> junk = Decode("P2 2 1 255 1 x\n");
  ASSERT_FALSE(junk.ok());
  EXPECT_THAT(junk.status().message(), HasSubstr("expected a decimal number, found 'x'"));
}

TEST(PgmTest, TrailingWhitespaceIsFineTrailingDataIsNot) {
  const std::string good = std::string("P5 2 1 255\n") + '\x01' + '\x02';
  EXPECT_TRUE(Decode(good + "\n \n").ok());
  const StatusOr<PgmImage> junk = Decode(good + "junk");
  ASSERT_FALSE(junk.ok());
  EXPECT_EQ(junk.status().message(), "mem.pgm: unexpected data after the pixels at byte 13 ('j')");
  PgmReadOptions tolerant;
  tolerant.allow_trailing_data = true;
  const StatusOr<PgmImage> tolerated = Decode(good + "junk", tolerant);
  ASSERT_TRUE(tolerated.ok()) << tolerated.status();
  EXPECT_EQ(tolerated->pixels, (std::vector<uint16_t>{1, 2}));
}

PgmImage RandomImage(std::mt19937& rng, int max_value) {
  std::uniform_int_distribution<int> size(1, 40);
  PgmImage image;
  image.width = size(rng);
  image.height = size(rng);
  image.max_value = max_value;
  std::uniform_int_distribution<int> sample(0, max_value);
  for (int i = 0; i < image.width * image.height; ++i) {
    image.pixels.push_back(static_cast<uint16_t>(sample(rng)));
  }
  return image;
}

TEST(PgmTest, EncodeDecodeRoundTripsBothEncodingsAndDepths) {
  std::mt19937 rng(7);
  for (const int max_value : {1, 100, 255, 256, 1000, 65535}) {
    for (const PgmEncoding encoding : {PgmEncoding::kBinary, PgmEncoding::kAscii}) {
      const PgmImage image = RandomImage(rng, max_value);
      const StatusOr<std::string> bytes = EncodePgm(image, encoding);
      ASSERT_TRUE(bytes.ok()) << bytes.status();
      const StatusOr<PgmImage> decoded = Decode(*bytes);
      ASSERT_TRUE(decoded.ok()) << decoded.status();
      EXPECT_EQ(*decoded, image) << "maxval " << max_value;
    }
  }
}

TEST(PgmTest, WritesFilesThatReadBack) {
  std::mt19937 rng(11);
  const PgmImage image = RandomImage(rng, 65535);
  const std::string path =
      ::testing::TempDir() + "/pgm_test_write_" + std::to_string(getpid()) + ".pgm";
  ASSERT_TRUE(WritePgm(image, path, PgmEncoding::kBinary).ok());
  const StatusOr<PgmImage> read = ReadPgm(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(*read, image);
  std::filesystem::remove(path);
}

TEST(PgmTest, RefusesToWriteInvalidImages) {
  PgmImage image;
  image.width = 2;
  image.height = 1;
  image.max_value = 10;
  image.pixels = {3};
  EXPECT_THAT(ValidatePgmImage(image, "x.pgm").message(), HasSubstr("1 pixels for a 2 x 1"));
  image.pixels = {3, 11};
  EXPECT_THAT(ValidatePgmImage(image, "x.pgm").message(),
              HasSubstr("pixel (1, 0) is 11, above maxval 10"));
  image.max_value = 0;
  EXPECT_FALSE(EncodePgm(image).ok());
  image = PgmImage{};
  EXPECT_FALSE(ValidatePgmImage(image, "x.pgm").ok());
  EXPECT_FALSE(WritePgm(image, ::testing::TempDir() + "/never.pgm").ok());
}

// Mutates valid PGMs thousands of times (seeded, so failures reproduce): the reader must return
// either an error or an image that satisfies its contract, and never crash or over-allocate.
TEST(PgmTest, FuzzedInputsNeverCrash) {
  std::mt19937 rng(20240611);
  std::vector<std::string> seeds;
  for (const int max_value : {255, 65535, 100}) {
    for (const PgmEncoding encoding : {PgmEncoding::kBinary, PgmEncoding::kAscii}) {
      PgmImage image = RandomImage(rng, max_value);
      image.width = std::min(image.width, 6);
      image.height = std::min(image.height, 5);
      image.pixels.resize(static_cast<size_t>(image.width) * image.height);
      seeds.push_back(*EncodePgm(image, encoding));
    }
  }
  seeds.push_back("P2\n# c\n2 2 # c\n255\n1 2\n# c\n3 4\n");
  const std::string alphabet = "P25 \n\t#0123456789-+xe\r\xff";
  PgmReadOptions options;
  options.max_cells = 1 << 16;
  int errors = 0;
  int successes = 0;
  constexpr int kIterations = 20000;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    std::string bytes = seeds[rng() % seeds.size()];
    const int mutations = 1 + static_cast<int>(rng() % 4);
    for (int m = 0; m < mutations && !bytes.empty(); ++m) {
      const size_t at = rng() % bytes.size();
      switch (rng() % 6) {
        case 0:  // flip a byte
          bytes[at] = static_cast<char>(rng());
          break;
        case 1:  // truncate
          bytes.resize(at);
          break;
        case 2:  // insert a header-ish character
          bytes.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        case 3:  // delete a byte
          bytes.erase(at, 1);
          break;
        case 4:  // replace with a digit (grows numbers in the header)
          bytes[at] = static_cast<char>('0' + rng() % 10);
          break;
        default:  // duplicate a chunk
          bytes.insert(at, bytes.substr(at, rng() % 8));
          break;
      }
    }
    const StatusOr<PgmImage> image = DecodePgm(bytes, "fuzz.pgm", options);
    if (!image.ok()) {
      ++errors;
      EXPECT_THAT(image.status().message(), StartsWith("fuzz.pgm: "));
      continue;
    }
    ++successes;
    ASSERT_GT(image->width, 0);
    ASSERT_GT(image->height, 0);
    ASSERT_LE(static_cast<int64_t>(image->width) * image->height, options.max_cells);
    ASSERT_EQ(image->pixels.size(), static_cast<size_t>(image->width) * image->height);
    for (const uint16_t sample : image->pixels) ASSERT_LE(sample, image->max_value);
  }
  // Most mutations break the file; some (a changed pixel) do not. Both paths were exercised.
  EXPECT_GT(errors, kIterations / 4);
  EXPECT_GT(successes, 0);
}

}  // namespace
}  // namespace fleetmap::grid
