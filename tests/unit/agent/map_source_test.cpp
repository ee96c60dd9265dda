#include "robot_agent/map_source.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "common/grid/map_io.hpp"
#include "common/grid/pgm.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/map_update_writer.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::agent {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

// A map's files written the ways editors and map_saver write them. Every write gets a modification
// time one second after the previous one, set explicitly, so no test depends on the file system's
// timestamp granularity.
class MapFiles {
 public:
  explicit MapFiles(const testing::ScratchDir& dir) : dir_(dir) {}

  std::string yaml() const { return dir_.Path("map.yaml"); }
  std::string Path(const std::string& name) const { return dir_.Path(name); }

  // The YAML naming `image`, rewritten in place.
  void WriteYaml(const std::string& image, double resolution = 0.05) {
    WriteInPlace("map.yaml", YamlText(image, resolution));
  }
  static std::string YamlText(const std::string& image, double resolution) {
    return "image: " + image + "\nresolution: " + std::to_string(resolution) +
           "\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  }

  // Truncates the file and writes `bytes` into it: the inode stays.
  void WriteInPlace(const std::string& name, const std::string& bytes) {
    std::ofstream(Path(name), std::ios::binary | std::ios::trunc) << bytes;
    Stamp(Path(name));
  }

  // Writes `bytes` to a temporary file and renames it over `name`, as WriteFileAtomically does.
  // The temporary file gets the modification time `name` has, so only the inode tells them apart.
  void WriteAtomically(const std::string& name, const std::string& bytes) {
    const std::string temp = Path(name + ".tmp");
    std::ofstream(temp, std::ios::binary | std::ios::trunc) << bytes;
    fs::last_write_time(temp, fs::last_write_time(Path(name)));
    fs::rename(temp, Path(name));
  }

 private:
  void Stamp(const std::string& path) {
    fs::last_write_time(path, base_ + std::chrono::seconds(++writes_));
  }

  const testing::ScratchDir& dir_;
  const fs::file_time_type base_ = fs::file_time_type::clock::now() - std::chrono::hours(1);
  int writes_ = 0;
};

constexpr uint8_t kFreeShade = 254;
constexpr uint8_t kOccupiedShade = 0;

// A PGM of one shade.
std::string Picture(int width, int height, uint8_t shade) {
  grid::PgmImage image;
  image.width = width;
  image.height = height;
  image.pixels.assign(static_cast<size_t>(width) * height, shade);
  StatusOr<std::string> bytes = grid::EncodePgm(image);
  EXPECT_TRUE(bytes.ok()) << bytes.status();
  return bytes.ok() ? *bytes : std::string();
}

// What spdlog's default logger writes while this lives.
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(stream_);
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;

  std::string text() const { return stream_.str(); }
  int Count(const std::string& needle) const {
    const std::string all = text();
    int count = 0;
    for (size_t at = all.find(needle); at != std::string::npos; at = all.find(needle, at + 1)) {
      ++count;
    }
    return count;
  }

 private:
  std::ostringstream stream_;
  std::shared_ptr<spdlog::logger> previous_;
};

// A source on `files` (a.pgm, free, 4 x 3), its first map already taken.
std::unique_ptr<FileMapSource> StartOnFreeMap(MapFiles& files) {
  files.WriteInPlace("a.pgm", Picture(4, 3, kFreeShade));
  files.WriteYaml("a.pgm");
  StatusOr<std::unique_ptr<FileMapSource>> source = FileMapSource::Create(files.yaml());
  EXPECT_TRUE(source.ok()) << source.status();
  if (!source.ok()) return nullptr;
  const std::optional<grid::OccupancyGrid> first = (*source)->Poll();
  EXPECT_TRUE(first.has_value());
  if (first) {
    EXPECT_EQ(first->at(0, 0), grid::kFreeValue);
  }
  EXPECT_FALSE((*source)->Poll().has_value()) << "nothing changed";
  return std::move(source).value();
}

TEST(FileMapSourceTest, RereadsAnImageRewrittenAlone) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);

  files.WriteInPlace("a.pgm", Picture(4, 3, kOccupiedShade));  // same size, later mtime
  const std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->at(0, 0), grid::kOccupiedValue);
  EXPECT_FALSE(source->Poll().has_value());
}

TEST(FileMapSourceTest, WaitsForTheImageOfAYamlWrittenFirst) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);
  LogCapture log;

  files.WriteYaml("b.pgm", 0.1);  // b.pgm does not exist yet: keep the map, say so once
  EXPECT_FALSE(source->Poll().has_value());
  EXPECT_FALSE(source->Poll().has_value());
  EXPECT_EQ(log.Count(files.Path("b.pgm") + ": no such file"), 1) << log.text();

  files.WriteInPlace("b.pgm", Picture(5, 2, kOccupiedShade));
  const std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->width(), 5);
  EXPECT_EQ(map->resolution(), 0.1);
  EXPECT_EQ(map->at(0, 0), grid::kOccupiedValue);
  EXPECT_FALSE(source->Poll().has_value());
}

TEST(FileMapSourceTest, FollowsAnImageWrittenBeforeTheYamlThatNamesIt) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);

  files.WriteInPlace("b.pgm", Picture(5, 2, kOccupiedShade));
  EXPECT_FALSE(source->Poll().has_value()) << "no file of the map changed yet";
  files.WriteYaml("b.pgm", 0.1);
  const std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->width(), 5);
  EXPECT_EQ(map->resolution(), 0.1);
  EXPECT_EQ(map->at(0, 0), grid::kOccupiedValue);
}

TEST(FileMapSourceTest, SeesFilesRenamedOverTheOldOnes) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);

  // Same size and modification time: only the inode differs.
  files.WriteAtomically("a.pgm", Picture(4, 3, kOccupiedShade));
  std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->at(0, 0), grid::kOccupiedValue);
  EXPECT_FALSE(source->Poll().has_value());

  files.WriteAtomically("map.yaml", MapFiles::YamlText("a.pgm", 0.25));
  map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->resolution(), 0.25);
}

TEST(FileMapSourceTest, RetriesAHalfWrittenImageUntilItIsWhole) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);
  LogCapture log;

  const std::string whole = Picture(4, 3, kOccupiedShade);
  files.WriteInPlace("a.pgm", whole.substr(0, whole.size() - 5));
  for (int poll = 0; poll < 3; ++poll) EXPECT_FALSE(source->Poll().has_value());
  EXPECT_EQ(log.Count("a.pgm: truncated"), 1) << log.text();

  files.WriteInPlace("a.pgm", whole.substr(0, whole.size() - 2));  // further along
  EXPECT_FALSE(source->Poll().has_value());

  files.WriteInPlace("a.pgm", whole);
  const std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->at(0, 0), grid::kOccupiedValue);
  EXPECT_EQ(log.Count("can be read again"), 1) << log.text();
}

TEST(FileMapSourceTest, RetriesAHalfWrittenPng) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);

  ASSERT_TRUE(grid::SaveMap(grid::OccupancyGrid(40, 30, 0.05, Pose2{}, grid::kOccupiedValue),
                            files.Path("saved.yaml"), {.image_format = "png"})
                  .ok());
  const std::string whole = testing::ReadFile(files.Path("saved.png"));
  ASSERT_GT(whole.size(), 20u);
  files.WriteInPlace("b.png", whole.substr(0, whole.size() / 2));
  files.WriteYaml("b.png");
  EXPECT_FALSE(source->Poll().has_value());
  EXPECT_FALSE(source->Poll().has_value());

  files.WriteInPlace("b.png", whole);
  const std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->width(), 40);
  EXPECT_EQ(map->at(0, 0), grid::kOccupiedValue);
}

TEST(FileMapSourceTest, KeepsTheMapThroughABrokenYaml) {
  testing::ScratchDir dir("file_map_source");
  MapFiles files(dir);
  auto source = StartOnFreeMap(files);
  ASSERT_NE(source, nullptr);
  LogCapture log;

  const std::string text = MapFiles::YamlText("a.pgm", 0.5);
  files.WriteInPlace("map.yaml", text.substr(0, 20));  // cut mid-way by the writer
  EXPECT_FALSE(source->Poll().has_value());
  EXPECT_FALSE(source->Poll().has_value());
  EXPECT_EQ(log.Count(files.yaml() + ": "), 1) << log.text();

  files.WriteInPlace("map.yaml", text);
  const std::optional<grid::OccupancyGrid> map = source->Poll();
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->resolution(), 0.5);
}

std::optional<grid::OccupancyGrid> PollUntil(
    MapSource& source, const std::function<bool(const grid::OccupancyGrid&)>& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  std::optional<grid::OccupancyGrid> last;
  while (std::chrono::steady_clock::now() < deadline) {
    if (auto map = source.Poll()) last = std::move(map);
    if (last && done(*last)) return last;
    std::this_thread::sleep_for(milliseconds(20));
  }
  return last;
}

TEST(TopicMapSourceTest, FollowsFullMapsAndTheirUpdates) {
  transport::ParticipantOptions options;
  options.domain_id = process::RandomDomainId();
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  auto slam = transport::Participant::Create(options);
  auto agent = transport::Participant::Create(options);
  ASSERT_TRUE(slam.ok() && agent.ok());

  auto source = TopicMapSource::Create(**agent, "rt/map");
  ASSERT_TRUE(source.ok()) << source.status();
  auto map_writer = transport::OccupancyGridWriter::Create(**slam, "rt/map");
  auto update_writer = transport::MapUpdateWriter::Create(**slam, "rt/map_updates");
  ASSERT_TRUE(map_writer.ok() && update_writer.ok());

  transport::MapMessage full;
  full.grid = grid::OccupancyGrid(8, 6, 0.05, Pose2{}, grid::kFreeValue);
  ASSERT_TRUE((*map_writer)->Write(full).ok());
  auto map = PollUntil(**source, [](const auto&) { return true; });
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->data(), full.grid.data());

  // A 2 x 2 update at (3, 1) marks four cells occupied; an update outside the map is refused.
  transport::MapUpdate outside{.x = 7,
                               .y = 5,
                               .width = 2,
                               .height = 2,
                               .data = std::vector<int8_t>(4, grid::kOccupiedValue),
                               .stamp = {}};
  transport::MapUpdate inside{.x = 3,
                              .y = 1,
                              .width = 2,
                              .height = 2,
                              .data = std::vector<int8_t>(4, grid::kOccupiedValue),
                              .stamp = {}};
  const auto patched = [](const grid::OccupancyGrid& g) {
    return g.at(3, 1) == grid::kOccupiedValue && g.at(4, 2) == grid::kOccupiedValue;
  };
  std::optional<grid::OccupancyGrid> updated;
  for (int attempt = 0; attempt < 100 && !(updated && patched(*updated)); ++attempt) {
    (void)(*update_writer)->Write(outside);
    (void)(*update_writer)->Write(inside);
    std::this_thread::sleep_for(milliseconds(50));
    if (auto polled = (*source)->Poll()) updated = std::move(polled);
  }
  ASSERT_TRUE(updated.has_value());
  EXPECT_TRUE(patched(*updated));
  EXPECT_EQ(updated->at(2, 1), grid::kFreeValue);
  EXPECT_EQ(updated->at(7, 5), grid::kFreeValue);  // the refused update changed nothing
}

}  // namespace
}  // namespace fleetmap::agent
