#include "common/grid/map_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "common/core/number_format.hpp"
#include "common/grid/pgm.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/unit/grid/crafted_png.hpp"

namespace fleetmap::grid {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using Rows = std::vector<std::vector<int>>;

std::string DataPath(const std::string& name) {
  return std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/" + name;
}

// The grid's values as the picture shows them: top row (grid row height - 1) first.
Rows PictureRows(const OccupancyGrid& grid) {
  Rows rows;
  for (int y = grid.height() - 1; y >= 0; --y) {
    std::vector<int> row;
    for (int x = 0; x < grid.width(); ++x) row.push_back(grid.at(x, y));
    rows.push_back(row);
  }
  return rows;
}

LoadedMap LoadOk(const std::string& name) {
  StatusOr<LoadedMap> map = LoadMap(DataPath(name));
  EXPECT_TRUE(map.ok()) << map.status();
  return map.ok() ? std::move(map).value() : LoadedMap{};
}

Status LoadError(const std::string& yaml_path, const MapLoadOptions& options = {}) {
  const StatusOr<LoadedMap> map = LoadMap(yaml_path, options);
  EXPECT_FALSE(map.ok()) << yaml_path << " loaded";
  return map.status();
}

// A fresh directory per test for files the test writes.
class TempDir {
 public:
  // The process id keeps concurrent runs (two build trees, ctest -j) apart.
  explicit TempDir(const std::string& name)
      : path_(fs::path(::testing::TempDir()) / (name + "_" + std::to_string(getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string Write(const std::string& name, const std::string& content) const {
    const fs::path file = path_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << content;
    return file.string();
  }
  std::string Path(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

// The shades of trinary_4x3.pgm, top row first: 0 89 90 255 / 204 205 254 100 / 206 50 230 1.

TEST(MapIoTest, LoadsTrinaryCellByCell) {
  const LoadedMap map = LoadOk("trinary_4x3.yaml");
  EXPECT_EQ(map.grid.width(), 4);
  EXPECT_EQ(map.grid.height(), 3);
  EXPECT_EQ(map.grid.resolution(), 0.5);
  EXPECT_EQ(map.grid.origin(), (Pose2{-1.0, 2.0, 0.0}));
  EXPECT_EQ(map.metadata.mode, MapMode::kTrinary);
  EXPECT_FALSE(map.metadata.negate);
  EXPECT_EQ(map.metadata.occupied_thresh, 0.65);
  EXPECT_EQ(map.metadata.free_thresh, 0.196);
  EXPECT_EQ(map.metadata.image, "trinary_4x3.pgm");
  EXPECT_EQ(map.metadata.image_path, DataPath("trinary_4x3.pgm"));
  // occ = 1 - v/255: 89 -> 0.6510 > 0.65 occupied; 90 -> 0.6471 unknown; 205 -> 0.19608 is not
  // below 0.196, unknown; 206 -> 0.1922 free; 100 -> 0.6078 unknown.
  EXPECT_EQ(PictureRows(map.grid), (Rows{{100, 100, -1, 0}, {-1, -1, 0, -1}, {0, 100, 0, 100}}));
  // Grid row 0 is the picture's bottom row.
  EXPECT_EQ(map.grid.at(0, 0), 0);
  EXPECT_EQ(map.grid.at(0, 2), 100);
}

TEST(MapIoTest, NegateSwapsDarkAndLight) {
  const LoadedMap map = LoadOk("negate_4x3.yaml");
  EXPECT_TRUE(map.metadata.negate);
  // occ = v/255: 50 -> 0.19608 unknown, 1 -> 0.0039 free, 204 -> 0.8 occupied, 100 -> 0.392.
  EXPECT_EQ(PictureRows(map.grid),
            (Rows{{0, -1, -1, 100}, {100, 100, 100, -1}, {100, -1, 100, 0}}));
}

TEST(MapIoTest, ThresholdsMoveTheBoundaries) {
  const LoadedMap map = LoadOk("thresholds_4x3.yaml");  // occupied 0.5, free 0.3, negate: false
  EXPECT_EQ(map.metadata.occupied_thresh, 0.5);
  EXPECT_EQ(map.metadata.free_thresh, 0.3);
  EXPECT_FALSE(map.metadata.negate);
  EXPECT_EQ(PictureRows(map.grid), (Rows{{100, 100, 100, 0}, {0, 0, 0, 100}, {0, 100, 0, 100}}));
}

TEST(MapIoTest, ScaleModeInterpolatesBetweenThresholds) {
  const LoadedMap map = LoadOk("scale_pgm_4x3.yaml");
  EXPECT_EQ(map.metadata.mode, MapMode::kScale);
  // rint((occ - 0.196) / (0.65 - 0.196) * 100): 90 -> 99.35 -> 99; 204 -> 0.88 -> 1;
  // 205 -> 0.017 -> 0; 100 -> 90.71 -> 91.
  EXPECT_EQ(PictureRows(map.grid), (Rows{{100, 100, 99, 0}, {1, 0, 0, 91}, {0, 100, 0, 100}}));
}

TEST(MapIoTest, ScaleModeReadsAlphaAsUnknownAndAveragesColour) {
  // scale_4x3.png, RGBA top row first:
  //   (0,0,0,255) (255,255,255,255) (128,128,128,0) (90,90,90,255)
  //   (100,100,100,255) (255,0,0,255) (30,60,90,255) (10,10,10,128)
  //   (204,204,204,255) (205,205,205,255) (150,150,150,255) (120,120,120,255)
  const LoadedMap map = LoadOk("scale_4x3.yaml");
  // red averages to 85 -> occ 0.667 occupied; (30,60,90) -> 60 -> occupied; 150 -> 47.5 -> 48;
  // 120 -> 73.4 -> 73; alpha 0 and alpha 128 -> unknown.
  EXPECT_EQ(PictureRows(map.grid), (Rows{{100, 0, -1, 99}, {91, 100, 100, -1}, {1, 0, 48, 73}}));
}

TEST(MapIoTest, TrinaryAveragesAlphaIntoTheShadeLikeNav2) {
  const LoadedMap map = LoadOk("rgba_trinary_4x3.yaml");
  // shade = (r + g + b + a) / 4 / 255: black opaque -> 63.75 -> occ 0.75 occupied; (128,128,128,0)
  // -> 96 -> occ 0.62 unknown; 90 opaque -> 131.25 -> unknown; (10,10,10,128) -> 39.5 occupied;
  // 150 -> 176.25 -> occ 0.31 unknown; 120 -> 153.75 unknown; red -> 127.5 -> occ 0.5 unknown.
  EXPECT_EQ(PictureRows(map.grid), (Rows{{100, 0, -1, -1}, {-1, -1, -1, 100}, {0, 0, -1, -1}}));
}

TEST(MapIoTest, RawModeCopiesShadesAndIgnoresNegate) {
  const LoadedMap map = LoadOk("raw_4x3.yaml");  // negate: 1, which raw ignores
  EXPECT_EQ(map.metadata.mode, MapMode::kRaw);
  EXPECT_EQ(PictureRows(map.grid), (Rows{{0, 1, 50, 100}, {-1, -1, -1, 99}, {37, 3, 100, 0}}));
}

TEST(MapIoTest, Reads16BitAsciiWithFullPrecision) {
  const LoadedMap map = LoadOk("p2_16bit.yaml");
  // 32768 -> occ 0.49999 unknown; 12850 -> occ 0.80392 occupied; 52700 -> occ 0.19585 free
  // (it would be 205, unknown, in 8 bits).
  EXPECT_EQ(PictureRows(map.grid), (Rows{{100, 0, -1}, {0, 100, 0}}));
}

TEST(MapIoTest, CellValueFromShadeUsesStrictThresholds) {
  MapMetadata metadata;
  metadata.occupied_thresh = 0.5;
  metadata.free_thresh = 0.25;
  EXPECT_EQ(CellValueFromShade(0.5, true, metadata), -1);   // occ == occupied_thresh
  EXPECT_EQ(CellValueFromShade(0.75, true, metadata), -1);  // occ == free_thresh
  EXPECT_EQ(CellValueFromShade(0.49, true, metadata), 100);
  EXPECT_EQ(CellValueFromShade(0.76, true, metadata), 0);
  EXPECT_EQ(CellValueFromShade(0.0, false, metadata), 100);  // alpha matters only in scale mode
  metadata.mode = MapMode::kScale;
  EXPECT_EQ(CellValueFromShade(0.5, true, metadata), 100);  // rint(1.0 * 100)
  EXPECT_EQ(CellValueFromShade(0.75, true, metadata), 0);
  EXPECT_EQ(CellValueFromShade(0.625, true, metadata), 50);
  EXPECT_EQ(CellValueFromShade(0.0, false, metadata), -1);
  metadata.mode = MapMode::kRaw;
  EXPECT_EQ(CellValueFromShade(100.0 / 255.0, true, metadata), 100);
  EXPECT_EQ(CellValueFromShade(101.0 / 255.0, true, metadata), -1);
  EXPECT_EQ(CellValueFromShade(0.0, false, metadata), 0);
}

TEST(MapIoTest, ModeNamesRoundTrip) {
  for (const MapMode mode : {MapMode::kTrinary, MapMode::kScale, MapMode::kRaw}) {
    EXPECT_EQ(MapModeFromName(MapModeName(mode)), mode);
  }
  EXPECT_FALSE(MapModeFromName("Trinary").has_value());
  EXPECT_FALSE(MapModeFromName("").has_value());
}

TEST(MapIoTest, MissingFilesAreNotFoundAndNamed) {
  Status status = LoadError(DataPath("no_such_map.yaml"));
  EXPECT_EQ(status.code(), StatusCode::kNotFound);
  EXPECT_EQ(status.message(), DataPath("no_such_map.yaml") + ": no such file");
  status = LoadError(FLEETMAP_TEST_DATA_DIR);
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("is not a regular file"));
  status = LoadError(DataPath("missing_image.yaml"));
  EXPECT_EQ(status.code(), StatusCode::kNotFound);
  EXPECT_EQ(status.message(), DataPath("does_not_exist.pgm") + ": no such file (the image of " +
                                  DataPath("missing_image.yaml") + ")");
}

TEST(MapIoTest, BadYamlFixturesFailWithClearMessages) {
  struct Case {
    std::string yaml;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"syntax_error.yaml", "YAML syntax error at line 3"},
      {"no_resolution.yaml", "missing required key 'resolution'"},
      {"zero_resolution.yaml", "line 2: resolution must be > 0 metres per cell, got 0"},
      {"negative_resolution.yaml", "resolution must be > 0 metres per cell, got -0.05"},
      {"unknown_mode.yaml", "line 2: unknown mode 'ternary', expected trinary, scale or raw"},
      {"escaping_path.yaml", "image '../maps/../trinary_4x3.pgm' is outside the YAML's directory"},
  };
  for (const Case& c : cases) {
    const Status status = LoadError(DataPath(c.yaml));
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << c.yaml;
    EXPECT_THAT(status.message(), StartsWith(DataPath(c.yaml) + ": ")) << c.yaml;
    EXPECT_THAT(status.message(), HasSubstr(c.message)) << c.yaml;
  }
}

TEST(MapIoTest, BadImageFixturesFailNamingTheImage) {
  Status status = LoadError(DataPath("bad_magic.yaml"));
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), StartsWith(DataPath("bad_magic.pgm") + ": not a PGM file"));
  status = LoadError(DataPath("truncated.yaml"));
  EXPECT_EQ(status.code(), StatusCode::kDataLoss);
  EXPECT_EQ(status.message(), DataPath("truncated.pgm") +
                                  ": truncated: expected 12 bytes of pixels (4 x 3 x 1), found 5");
  status = LoadError(DataPath("size_mismatch.yaml"));
  EXPECT_EQ(status.code(), StatusCode::kDataLoss);
  EXPECT_THAT(status.message(),
              HasSubstr("size_mismatch.pgm: truncated: expected 12 pixel values"));
  status = LoadError(DataPath("absurd_size.yaml"));
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(status.message(), StartsWith(DataPath("absurd_size.pgm") + ": image is 100000 x"));
}

TEST(MapIoTest, MaxCellsAppliesToPngBeforeDecoding) {
  MapLoadOptions options;
  options.max_cells = 11;
  const Status status = LoadError(DataPath("scale_4x3.yaml"), options);
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(status.message(), HasSubstr("scale_4x3.png: image is 4 x 3 = 12 cells"));
  options.max_cells = 12;
  EXPECT_TRUE(LoadMap(DataPath("scale_4x3.yaml"), options).ok());
}

constexpr char kYamlTail[] =
    "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

TEST(MapIoTest, RefusesAPngThatWouldDecodeTooLargeBeforeDecodingIt) {
  TempDir dir("map_io_decoded_bytes");
  // 10000 x 10000 is under max_cells, but RGBA at 16 bits decodes to 800 MB: refused from the
  // header. The file holds no pixel data, so decoding would have failed with kDataLoss instead.
  dir.Write("rgba16.png", testing::PngHead(10000, 10000, 16, 6));
  Status status =
      LoadError(dir.Write("rgba16.yaml", std::string("image: rgba16.png\n") + kYamlTail));
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(status.message(), dir.Path("rgba16.png") +
                                  ": image is 10000 x 10000 with 4 channel(s) of 16 bits, "
                                  "800000000 bytes decoded, more than the limit of 268435456 "
                                  "bytes (max_decoded_bytes)");

  // 60000 x 60000 is over both limits; with the cell limit lifted the byte limit still holds.
  dir.Write("huge.png", testing::PngHead(60000, 60000, 16, 6));
  const std::string huge = dir.Write("huge.yaml", std::string("image: huge.png\n") + kYamlTail);
  status = LoadError(huge);
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(status.message(), HasSubstr("60000 x 60000 = 3600000000 cells"));
  MapLoadOptions options;
  options.max_cells = std::numeric_limits<int64_t>::max();
  status = LoadError(huge, options);
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(status.message(), HasSubstr("28800000000 bytes decoded"));

  // Under both limits the same header reaches the decoder, which finds no pixels.
  options.max_decoded_bytes = std::numeric_limits<int64_t>::max();
  EXPECT_EQ(
      LoadError(dir.Write("small.yaml", std::string("image: rgba16.png\n") + kYamlTail), options)
          .code(),
      StatusCode::kDataLoss);
}

TEST(MapIoTest, MaxDecodedBytesIsAnInclusiveLimitForPngAndPgm) {
  TempDir dir("map_io_decoded_bytes_limit");
  // 4 x 3 RGBA at 16 bits: 96 bytes decoded.
  ASSERT_TRUE(cv::imwrite(dir.Path("rgba.png"), cv::Mat(3, 4, CV_16UC4, cv::Scalar::all(65535))));
  const std::string png_yaml = dir.Write("png.yaml", std::string("image: rgba.png\n") + kYamlTail);
  // 4 x 3 PGM: 12 samples held in 16 bits, 24 bytes.
  const std::string pgm_yaml = DataPath("raw_4x3.yaml");
  MapLoadOptions options;
  options.max_decoded_bytes = 96;
  EXPECT_TRUE(LoadMap(png_yaml, options).ok());
  options.max_decoded_bytes = 95;
  EXPECT_EQ(LoadError(png_yaml, options).code(), StatusCode::kResourceExhausted);
  options.max_decoded_bytes = 24;
  EXPECT_TRUE(LoadMap(pgm_yaml, options).ok());
  options.max_decoded_bytes = 23;
  const Status status = LoadError(pgm_yaml, options);
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(status.message(),
              HasSubstr("raw_4x3.pgm: image is 4 x 3 with 1 channel(s) of 16 bits"));
}

TEST(MapIoTest, RefusesImageFormatsWhoseSizeIsNotCheckedBeforeDecoding) {
  TempDir dir("map_io_other_formats");
  ASSERT_TRUE(cv::imwrite(dir.Path("map.bmp"), cv::Mat(3, 4, CV_8UC1, cv::Scalar::all(254))));
  const StatusOr<LoadedMap> bmp =
      LoadMap(dir.Write("bmp.yaml", std::string("image: map.bmp\n") + kYamlTail));
  ASSERT_TRUE(bmp.ok()) << bmp.status();
  EXPECT_EQ(bmp->grid.width(), 4);
  EXPECT_EQ(bmp->grid.at(0, 0), kFreeValue);

  dir.Write("map.gif", "GIF89a" + std::string(40, '\0'));
  const Status gif = LoadError(dir.Write("gif.yaml", std::string("image: map.gif\n") + kYamlTail));
  EXPECT_EQ(gif.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(gif.message(), StartsWith(dir.Path("map.gif") + ": not a PGM, PNG or BMP image"));
}

TEST(MapIoTest, EscapingPathIsAllowedOnlyWhenAsked) {
  MapLoadOptions options;
  options.allow_outside_dir = true;
  // Allowed, so the error is now that the file outside does not exist.
  const Status status = LoadError(DataPath("escaping_path.yaml"), options);
  EXPECT_EQ(status.code(), StatusCode::kNotFound);
  EXPECT_THAT(status.message(), HasSubstr("trinary_4x3.pgm: no such file"));
}

TEST(MapIoTest, PathRulesAreLexicalAndAllowAbsolutePathsInside) {
  const TempDir dir("map_io_path_rules");
  const std::string tail =
      "resolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  dir.Write("maps/trinary_4x3.pgm", "P2 1 1 255 0\n");
  dir.Write("outside.pgm", "P2 1 1 255 0\n");
  // `..` that comes back inside is fine.
  EXPECT_TRUE(LoadMap(dir.Write("maps/a.yaml", "image: ../maps/trinary_4x3.pgm\n" + tail)).ok());
  // An absolute path inside the directory is fine; outside it is refused unless allowed.
  EXPECT_TRUE(
      LoadMap(dir.Write("maps/b.yaml", "image: " + dir.Path("maps/trinary_4x3.pgm") + "\n" + tail))
          .ok());
  const std::string outside =
      dir.Write("maps/c.yaml", "image: " + dir.Path("outside.pgm") + "\n" + tail);
  EXPECT_THAT(LoadError(outside).message(), HasSubstr("is outside the YAML's directory"));
  MapLoadOptions options;
  options.allow_outside_dir = true;
  EXPECT_TRUE(LoadMap(outside, options).ok());
  EXPECT_THAT(LoadError(dir.Write("maps/d.yaml", "image: ../outside.pgm\n" + tail)).message(),
              HasSubstr("is outside the YAML's directory"));
}

TEST(MapIoTest, RejectsBadKeys) {
  const TempDir dir("map_io_bad_keys");
  dir.Write("m.pgm", "P2 1 1 255 0\n");
  const std::string image = "image: m.pgm\n";
  const std::string resolution = "resolution: 0.05\n";
  const std::string origin = "origin: [0, 0, 0]\n";
  const std::string negate = "negate: 0\n";
  const std::string thresholds = "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  struct Case {
    std::string yaml;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"", "expected a YAML mapping"},
      {"- a\n- b\n", "expected a YAML mapping"},
      {resolution + origin + negate + thresholds, "missing required key 'image'"},
      {"image: ''\n" + resolution + origin + negate + thresholds, "image must be a non-empty"},
      {"image: [a, b]\n" + resolution + origin + negate + thresholds, "got a list of 2 items"},
      {image + origin + negate + thresholds, "missing required key 'resolution'"},
      {image + "resolution: abc\n" + origin + negate + thresholds,
       "resolution must be a number, got 'abc'"},
      {image + "resolution: .nan\n" + origin + negate + thresholds, "resolution must be finite"},
      {image + "resolution: .inf\n" + origin + negate + thresholds, "resolution must be finite"},
      {image + resolution + negate + thresholds, "missing required key 'origin'"},
      {image + resolution + "origin: [0, 0]\n" + negate + thresholds,
       "origin must be a list of 3 numbers [x, y, yaw], got a list of 2 items"},
      {image + resolution + "origin: 5\n" + negate + thresholds, "origin must be a list of 3"},
      {image + resolution + "origin: [0, x, 0]\n" + negate + thresholds,
       "origin y must be a number, got 'x'"},
      {image + resolution + origin + thresholds, "missing required key 'negate'"},
      {image + resolution + origin + "negate: 2\n" + thresholds, "negate must be 0 or 1, got '2'"},
      {image + resolution + origin + "negate: maybe\n" + thresholds, "negate must be 0 or 1"},
      {image + resolution + origin + negate + "free_thresh: 0.1\n",
       "missing required key 'occupied_thresh'"},
      {image + resolution + origin + negate + "occupied_thresh: 0.65\n",
       "missing required key 'free_thresh'"},
      {image + resolution + origin + negate + "occupied_thresh: 1.5\nfree_thresh: 0.1\n",
       "occupied_thresh must be in [0, 1], got 1.5"},
      {image + resolution + origin + negate + "occupied_thresh: 0.65\nfree_thresh: -0.1\n",
       "free_thresh must be in [0, 1], got -0.1"},
      {image + resolution + origin + negate + "occupied_thresh: 0.5\nfree_thresh: 0.5\n",
       "free_thresh (0.5) must be below occupied_thresh (0.5)"},
      {image + resolution + origin + negate + thresholds + "mode: [trinary]\n", "unknown mode"},
      {image + resolution + origin + negate + thresholds + "mode: TRINARY\n",
       "unknown mode 'TRINARY'"},
  };
  int index = 0;
  for (const Case& c : cases) {
    const std::string path = dir.Write("case" + std::to_string(index++) + ".yaml", c.yaml);
    const Status status = LoadError(path);
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << c.yaml;
    EXPECT_THAT(status.message(), StartsWith(path + ": ")) << c.yaml;
    EXPECT_THAT(status.message(), HasSubstr(c.message)) << c.yaml;
  }
  const Status huge = LoadError(dir.Write("huge.yaml", "# " + std::string(2 << 20, 'x') + "\n"));
  EXPECT_EQ(huge.code(), StatusCode::kResourceExhausted);
  EXPECT_THAT(huge.message(), HasSubstr("huge.yaml: YAML file is"));
  // negate also accepts booleans; unknown keys are ignored, as in nav2.
  EXPECT_TRUE(LoadMap(dir.Write("ok.yaml", image + resolution + origin + "negate: true\n" +
                                               thresholds + "extra: 1\n"))
                  .ok());
}

OccupancyGrid GridOfRows(const Rows& picture_rows, double resolution, Pose2 origin) {
  const int height = static_cast<int>(picture_rows.size());
  const int width = static_cast<int>(picture_rows.front().size());
  OccupancyGrid grid(width, height, resolution, origin);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      grid.at(x, y) = static_cast<int8_t>(picture_rows[height - 1 - y][x]);
    }
  }
  return grid;
}

// Issue 33: the YAML carries the numbers the map was made with, as nav2's map_saver does: a
// resolution that crossed a float32 field (taken back as its decimal) is 0.05, and an origin
// computed from tile indices (-3 * 12.8 = -38.400000000000006) is -38.4.
TEST(MapIoTest, SavesCleanNumbers) {
  const TempDir dir("map_io_save_clean");
  const OccupancyGrid grid =
      GridOfRows({{0, 100}}, DoubleFromFloat(0.05F), Pose2{-3 * 12.8, 1687 * 0.025, 1e-17});
  const std::string yaml = dir.Path("clean.yaml");
  ASSERT_TRUE(SaveMap(grid, yaml).ok());
  const std::string text = fleetmap::testing::ReadFile(yaml);
  EXPECT_THAT(text, HasSubstr("resolution: 0.05\n"));
  EXPECT_THAT(text, HasSubstr("origin: [-38.4, 42.175, 0]\n"));
  EXPECT_THAT(text, HasSubstr("occupied_thresh: 0.65\n"));
  EXPECT_THAT(text, HasSubstr("free_thresh: 0.196\n"));
  const StatusOr<LoadedMap> loaded = LoadMap(yaml);
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(loaded->grid.resolution(), 0.05);
  EXPECT_NEAR(loaded->grid.origin().x, grid.origin().x, 1e-12);
}

TEST(MapIoTest, SavesTrinaryWithNav2Shades) {
  const TempDir dir("map_io_save_trinary");
  const OccupancyGrid grid =
      GridOfRows({{-1, 0, 10, 19, 20}, {50, 64, 65, 100, -1}}, 0.05, Pose2{-12.345, 6.5, 0.25});
  const std::string yaml = dir.Path("out.yaml");
  ASSERT_TRUE(SaveMap(grid, yaml).ok());
  const StatusOr<PgmImage> image = ReadPgm(dir.Path("out.pgm"));
  ASSERT_TRUE(image.ok()) << image.status();
  // free_thresh 0.196 -> rint(19.6) = 20: values <= 20 are free (254); occupied from 65 (0).
  EXPECT_EQ(image->pixels, (std::vector<uint16_t>{205, 254, 254, 254, 254, 205, 205, 0, 0, 205}));
  const YAML::Node node = YAML::LoadFile(yaml);
  EXPECT_EQ(node["image"].as<std::string>(), "out.pgm");
  EXPECT_EQ(node["mode"].as<std::string>(), "trinary");
  EXPECT_EQ(node["resolution"].as<double>(), 0.05);
  EXPECT_EQ(node["origin"][0].as<double>(), -12.345);
  EXPECT_EQ(node["origin"][1].as<double>(), 6.5);
  EXPECT_EQ(node["origin"][2].as<double>(), 0.25);
  EXPECT_EQ(node["negate"].as<int>(), 0);
  EXPECT_EQ(node["occupied_thresh"].as<double>(), 0.65);
  EXPECT_EQ(node["free_thresh"].as<double>(), 0.196);
  // Reading back gives the trinary view of the grid, with the same geometry.
  const StatusOr<LoadedMap> loaded = LoadMap(yaml);
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(PictureRows(loaded->grid), (Rows{{-1, 0, 0, 0, 0}, {-1, -1, 100, 100, -1}}));
  EXPECT_EQ(loaded->grid.origin(), grid.origin());
  EXPECT_EQ(loaded->grid.resolution(), grid.resolution());
}

TEST(MapIoTest, SavesScaleAsGrayWithAlphaPng) {
  const TempDir dir("map_io_save_scale");
  const OccupancyGrid grid = GridOfRows({{0, 50, 100, -1}}, 0.1, Pose2{});
  MapSaveOptions options;
  options.mode = MapMode::kScale;
  ASSERT_TRUE(SaveMap(grid, dir.Path("s.yaml"), options).ok());
  const cv::Mat png = cv::imread(dir.Path("s.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(png.type(), CV_8UC4);
  // (100 - v) / 100 * 255 gray, opaque; unknown transparent.
  EXPECT_EQ(png.at<cv::Vec4b>(0, 0), cv::Vec4b(255, 255, 255, 255));
  EXPECT_EQ(png.at<cv::Vec4b>(0, 1), cv::Vec4b(128, 128, 128, 255));
  EXPECT_EQ(png.at<cv::Vec4b>(0, 2), cv::Vec4b(0, 0, 0, 255));
  EXPECT_EQ(png.at<cv::Vec4b>(0, 3)[3], 0);
  const StatusOr<LoadedMap> loaded = LoadMap(dir.Path("s.yaml"));
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(loaded->metadata.mode, MapMode::kScale);
  // 128 -> occ 0.498 -> rint((0.498 - 0.196) / 0.454 * 100) = 67.
  EXPECT_EQ(PictureRows(loaded->grid), (Rows{{0, 67, 100, -1}}));
}

TEST(MapIoTest, ScaleToPgmNeedsAGridWithoutUnknownCells) {
  const TempDir dir("map_io_save_scale_pgm");
  MapSaveOptions options;
  options.mode = MapMode::kScale;
  options.image_format = "pgm";
  const Status status = SaveMap(GridOfRows({{0, -1}}, 0.1, Pose2{}), dir.Path("a.yaml"), options);
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("PGM has no alpha channel"));
  EXPECT_FALSE(fs::exists(dir.Path("a.yaml")));
  EXPECT_TRUE(SaveMap(GridOfRows({{0, 40}}, 0.1, Pose2{}), dir.Path("b.yaml"), options).ok());
  const StatusOr<PgmImage> image = ReadPgm(dir.Path("b.pgm"));
  ASSERT_TRUE(image.ok()) << image.status();
  EXPECT_EQ(image->pixels, (std::vector<uint16_t>{255, 153}));
}

TEST(MapIoTest, RawRoundTripsEveryValue) {
  const TempDir dir("map_io_save_raw");
  OccupancyGrid grid(103, 2, 0.25, Pose2{1.0, -2.0, 0.0});
  for (int x = 0; x < 103; ++x) {
    grid.at(x, 0) = static_cast<int8_t>(x - 1);               // -1 .. 101
    grid.at(x, 1) = static_cast<int8_t>(x % 2 ? -128 : 127);  // out-of-range values
  }
  MapSaveOptions options;
  options.mode = MapMode::kRaw;
  ASSERT_TRUE(SaveMap(grid, dir.Path("r.yaml"), options).ok());
  const StatusOr<LoadedMap> loaded = LoadMap(dir.Path("r.yaml"));
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  for (int x = 0; x < 103; ++x) {
    const int expected = x - 1 > 100 ? -1 : x - 1;
    EXPECT_EQ(loaded->grid.at(x, 0), expected) << x;
    EXPECT_EQ(loaded->grid.at(x, 1), -1) << x;
  }
}

TEST(MapIoTest, RefusesSavesThatWouldNotReadBack) {
  const TempDir dir("map_io_save_refuse");
  MapSaveOptions options;
  options.free_thresh = 0.25;  // nav2's old default: shade 205 (occ 0.196) would read back free
  const OccupancyGrid with_unknown = GridOfRows({{0, -1, 100}}, 0.1, Pose2{});
  const Status status = SaveMap(with_unknown, dir.Path("a.yaml"), options);
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("the trinary shade 205 would read back as 0"));
  // Without unknown cells the shade 205 is never written, so the same thresholds are fine.
  EXPECT_TRUE(SaveMap(GridOfRows({{0, 100}}, 0.1, Pose2{}), dir.Path("b.yaml"), options).ok());

  options = MapSaveOptions{};
  options.occupied_thresh = 1.0;  // black (occ 1.0) is not above 1.0
  EXPECT_THAT(SaveMap(with_unknown, dir.Path("c.yaml"), options).message(),
              HasSubstr("shade 0 would read back as -1"));
  options = MapSaveOptions{};
  options.free_thresh = 0.7;
  EXPECT_THAT(SaveMap(with_unknown, dir.Path("d.yaml"), options).message(),
              HasSubstr("must be below occupied_thresh"));
  options = MapSaveOptions{};
  options.image_format = "jpg";
  EXPECT_THAT(SaveMap(with_unknown, dir.Path("e.yaml"), options).message(),
              HasSubstr("image format 'jpg' is not supported"));
  EXPECT_THAT(SaveMap(OccupancyGrid(), dir.Path("f.yaml")).message(),
              HasSubstr("cannot save an empty grid"));
  EXPECT_THAT(SaveMap(with_unknown, dir.Path("g.pgm")).message(), HasSubstr("overwritten"));
}

MapSaveOptions SaveOptionsFor(const MapMetadata& metadata) {
  MapSaveOptions options;
  options.mode = metadata.mode;
  options.occupied_thresh = metadata.occupied_thresh;
  options.free_thresh = metadata.free_thresh;
  return options;
}

void ExpectRoundTrip(const std::string& yaml, const std::string& out_dir) {
  SCOPED_TRACE(yaml);
  const StatusOr<LoadedMap> first = LoadMap(yaml);
  ASSERT_TRUE(first.ok()) << first.status();
  const std::string saved = out_dir + "/" + fs::path(yaml).filename().string();
  ASSERT_TRUE(SaveMap(first->grid, saved, SaveOptionsFor(first->metadata)).ok());
  const StatusOr<LoadedMap> second = LoadMap(saved);
  ASSERT_TRUE(second.ok()) << second.status();
  EXPECT_EQ(second->grid.width(), first->grid.width());
  EXPECT_EQ(second->grid.height(), first->grid.height());
  EXPECT_EQ(second->grid.resolution(), first->grid.resolution());
  EXPECT_EQ(second->grid.origin(), first->grid.origin());
  EXPECT_TRUE(second->grid.data() == first->grid.data()) << "cell values differ";
  EXPECT_EQ(second->metadata.mode, first->metadata.mode);
  EXPECT_EQ(second->metadata.occupied_thresh, first->metadata.occupied_thresh);
  EXPECT_EQ(second->metadata.free_thresh, first->metadata.free_thresh);
}

TEST(MapIoTest, TinyTrinaryAndRawFixturesRoundTrip) {
  const TempDir dir("map_io_round_trip_fixtures");
  for (const char* name :
       {"trinary_4x3.yaml", "negate_4x3.yaml", "raw_4x3.yaml", "p2_16bit.yaml"}) {
    ExpectRoundTrip(DataPath(name), dir.Path(""));
  }
}

TEST(MapIoTest, EverySharedMapRoundTrips) {
  const fs::path maps_dir(FLEETMAP_SHARED_MAPS_DIR);
  if (!fs::is_directory(maps_dir)) GTEST_SKIP() << "no shared maps at " << maps_dir;
  const TempDir dir("map_io_round_trip_shared");
  int maps = 0;
  for (const auto& entry : fs::directory_iterator(maps_dir)) {
    if (entry.path().extension() != ".yaml") continue;
    ExpectRoundTrip(entry.path().string(), dir.Path(""));
    ++maps;
  }
  EXPECT_GT(maps, 0) << "no *.yaml in " << maps_dir;
}

}  // namespace
}  // namespace fleetmap::grid
