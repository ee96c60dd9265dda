// `fleetmap save-map`, the map saver, against a live server: what it writes loads back with
// fleetmap's own reader and matches rt/fleetmap/map cell for cell; no server, or a path that
// cannot be written, is a clear error. Real processes, DDS over loopback, a random domain.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "common/core/wake_up.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vmap_file.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;

// Bounds waits on a loaded 2-core CI machine; not an assertion about speed.
constexpr seconds kDeadline{60};

const std::string kMap = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml";

// The trinary value a map_server reader gives a fused cell once saved with `saved`'s thresholds.
int8_t Trinary(int8_t value, const grid::MapMetadata& saved) {
  if (value < 0) return -1;
  if (value >= saved.occupied_thresh * 100.0) return 100;
  if (value <= saved.free_thresh * 100.0) return 0;
  return -1;
}

// Issue 33: a 0.05 map is saved as `resolution: 0.05` (nav2's map_saver writes a clean 0.05), not
// the float32 of the DDS message widened (0.05000000074505806); no number in the YAML or the
// GeoJSON carries float noise (a run of ten or more decimals).
void ExpectCleanNumbers(const std::string& out, double fused_resolution) {
  EXPECT_EQ(fused_resolution, 0.05);
  const std::string yaml = testing::ReadFile(out + "/fused.yaml");
  EXPECT_THAT(yaml, HasSubstr("resolution: 0.05\n"));
  EXPECT_THAT(yaml, Not(ContainsRegex("[0-9]\\.[0-9]{10}")));
  EXPECT_THAT(testing::ReadFile(out + "/fused.geojson"), Not(ContainsRegex("[0-9]\\.[0-9]{10}")));
}

// No output of the tool, fed back to the tool, is refused: the saved map registers on the robot's
// map it was fused from (same resolution), and info, vectorize, validate and render read it and
// the saved .vmap.
void ExpectTheToolReadsWhatItWrote(const std::string& out) {
  const std::string saved = out + "/fused.yaml";
  const auto registered = testing::RunFleetmap({"register", saved, kMap});
  EXPECT_EQ(registered.exit_code, 0) << registered.output();
  EXPECT_THAT(registered.err, Not(HasSubstr("differs")));
  const auto info = testing::RunFleetmap({"info", saved});
  EXPECT_EQ(info.exit_code, 0) << info.output();
  EXPECT_THAT(info.out, HasSubstr("resolution: 0.05 m/cell"));
  const auto vectorized = testing::RunFleetmap({"vectorize", saved, "-o", out + "/again.vmap"});
  EXPECT_EQ(vectorized.exit_code, 0) << vectorized.output();
  const auto validated = testing::RunFleetmap({"validate", saved, out + "/again.vmap"});
  EXPECT_EQ(validated.exit_code, 0) << validated.output();
  const auto rendered = testing::RunFleetmap({"render", out + "/fused.vmap", "-o", out + "/f.svg"});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.output();
}

// Issue 33, GIS: `--georef` leaves the map YAML as it was (map_server's format, byte for byte),
// writes NAME.georef.yaml beside it, and the GeoJSON in WGS84 with the plane export's area; the
// tools read the saved map with the side file beside it. A later save without --georef leaves the
// side file and says so.
void ExpectGeoreferencedSave(const std::string& out, int domain) {
  EXPECT_FALSE(std::filesystem::exists(out + "/fused.georef.yaml")) << "only with --georef";
  const std::string geo = out + "/geo";
  std::filesystem::create_directories(geo);
  const std::vector<std::string> save = {"save-map",
                                         "-o",
                                         geo + "/fused.yaml",
                                         "--vmap",
                                         geo + "/fused.vmap",
                                         "--geojson",
                                         geo + "/fused.geojson",
                                         "--domain",
                                         std::to_string(domain),
                                         "--localhost-only",
                                         "--settle",
                                         "1"};
  std::vector<std::string> georeferenced = save;
  georeferenced.insert(georeferenced.end(), {"--georef", "-33.45", "-70.66", "135"});
  const auto saved = testing::RunFleetmap(georeferenced);
  ASSERT_EQ(saved.exit_code, 0) << saved.output();
  EXPECT_THAT(saved.out, HasSubstr(geo + "/fused.georef.yaml: the fleet frame's georeference"));
  EXPECT_EQ(testing::ReadFile(geo + "/fused.yaml"), testing::ReadFile(out + "/fused.yaml"));

  const YAML::Node side = YAML::LoadFile(geo + "/fused.georef.yaml");
  EXPECT_EQ(side["map"].as<std::string>(), "fused.yaml");
  EXPECT_EQ(side["frame"].as<std::string>(), "fleet");
  EXPECT_EQ(side["crs"].as<std::string>(), "EPSG:4326");
  EXPECT_EQ(side["latitude"].as<double>(), -33.45);
  EXPECT_EQ(side["longitude"].as<double>(), -70.66);
  EXPECT_EQ(side["yaw"].as<double>(), 135.0);

  const nlohmann::json plane = nlohmann::json::parse(testing::ReadFile(out + "/fused.geojson"));
  const nlohmann::json wgs84 = nlohmann::json::parse(testing::ReadFile(geo + "/fused.geojson"));
  EXPECT_FALSE(wgs84.contains("crs"));
  EXPECT_THAT(testing::GeoJsonProblems(wgs84, testing::GeoJsonCoordinates::kWgs84),
              ::testing::IsEmpty());
  const double plane_area = testing::PolygonArea(plane, testing::GeoJsonCoordinates::kFrameMetres);
  EXPECT_GT(plane_area, 10.0);
  EXPECT_NEAR(testing::PolygonArea(wgs84, testing::GeoJsonCoordinates::kWgs84), plane_area,
              1e-3 * plane_area);
  ExpectTheToolReadsWhatItWrote(geo);

  const auto again = testing::RunFleetmap(save);
  ASSERT_EQ(again.exit_code, 0) << again.output();
  EXPECT_THAT(again.err, HasSubstr(geo + "/fused.georef.yaml from an earlier save is left"));
  EXPECT_TRUE(std::filesystem::exists(geo + "/fused.georef.yaml"));
}

TEST(CliSaveMapTest, TheSavedMapIsTheFusedMapCellForCell) {
  const std::string out = testing::FreshTempDir("cli_save_map");
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  process::Subprocess server({testing::kServerBinary, "--duration", "120", "--no-object-learning",
                              "--no-extrapolation", "--map-period", "0.5"},
                             env);
  process::Subprocess agent({testing::kAgentBinary, "--robot-id", "alpha", "--map", kMap}, env);

  // What rt/fleetmap/map carries, until it has not changed for 3 s (the robot's map is static).
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  auto participant = transport::Participant::Create(options);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto maps =
      transport::OccupancyGridReader::Create(**participant, transport::kFleetMapTopic, wake_up);
  ASSERT_TRUE(maps.ok()) << maps.status();
  std::optional<grid::OccupancyGrid> fused;
  auto last_change = std::chrono::steady_clock::now();
  const auto deadline = last_change + kDeadline;
  while (std::chrono::steady_clock::now() < deadline &&
         (!fused || std::chrono::steady_clock::now() - last_change < seconds(3))) {
    wake_up->WaitFor(milliseconds(100));
    for (StatusOr<transport::MapMessage>& map : (*maps)->Drain()) {
      ASSERT_TRUE(map.ok()) << map.status();
      if (!fused || fused->data() != map->grid.data())
        last_change = std::chrono::steady_clock::now();
      fused = std::move(map->grid);
    }
  }
  ASSERT_TRUE(fused.has_value()) << server.Output();

  const auto saved =
      testing::RunFleetmap({"save-map", "-o", out + "/fused.yaml", "--vmap", out + "/fused.vmap",
                            "--geojson", out + "/fused.geojson", "--domain", std::to_string(domain),
                            "--localhost-only", "--settle", "1"});
  ASSERT_EQ(saved.exit_code, 0) << saved.output();
  EXPECT_TRUE(std::filesystem::exists(out + "/fused.pgm"));

  const auto loaded = grid::LoadMap(out + "/fused.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  const grid::OccupancyGrid& read = loaded->grid;
  ASSERT_EQ(read.width(), fused->width());
  ASSERT_EQ(read.height(), fused->height());
  EXPECT_DOUBLE_EQ(read.resolution(), fused->resolution());
  EXPECT_NEAR(read.origin().x, fused->origin().x, 1e-9);
  EXPECT_NEAR(read.origin().y, fused->origin().y, 1e-9);
  int64_t differing = 0;
  int64_t occupied = 0;
  for (int y = 0; y < read.height(); ++y) {
    for (int x = 0; x < read.width(); ++x) {
      differing += read.at(x, y) != Trinary(fused->at(x, y), loaded->metadata);
      occupied += read.at(x, y) == 100;
    }
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(occupied, 100) << "the house's walls";

  const auto vmap = transport::ReadVmapFile(out + "/fused.vmap");
  ASSERT_TRUE(vmap.ok()) << vmap.status();
  EXPECT_GT(vmap->tiles.size(), 0u);
  EXPECT_GT(vmap->ObstacleVertexCount(), 0u);
  EXPECT_THAT(testing::ReadFile(out + "/fused.geojson"), HasSubstr("FeatureCollection"));

  ExpectCleanNumbers(out, fused->resolution());
  ExpectTheToolReadsWhatItWrote(out);
  ExpectGeoreferencedSave(out, domain);

  maps->reset();
  std::filesystem::remove_all(out);
}

TEST(CliSaveMapTest, NoServerIsATimeoutNamingTheDomain) {
  const int domain = process::RandomDomainId();
  const std::string out = testing::FreshTempDir("cli_save_map_none");
  const auto saved = testing::RunFleetmap({"save-map", "-o", out + "/x.yaml", "--timeout", "2",
                                           "--domain", std::to_string(domain), "--localhost-only"});
  EXPECT_EQ(saved.exit_code, 1);
  EXPECT_THAT(saved.err, HasSubstr("no fused map"));
  EXPECT_THAT(saved.err, HasSubstr("domain " + std::to_string(domain)));
  EXPECT_FALSE(std::filesystem::exists(out + "/x.yaml"));
  std::filesystem::remove_all(out);
}

// Issue 33: with stderr on a pipe (a CI log, the journal, `| tail`) the wait's progress comes as
// whole lines, not '\r' updates running together into one: the first update and the final state,
// each on a line of its own (the updates each second between are held back: a line at most every
// 10 s), then the error on its own line.
TEST(CliSaveMapTest, ProgressToAPipeIsWholeLinesWithoutCarriageReturns) {
  const int domain = process::RandomDomainId();
  const std::string out = testing::FreshTempDir("cli_save_map_progress");
  const auto saved = testing::RunFleetmap({"save-map", "-o", out + "/x.yaml", "--timeout", "3",
                                           "--domain", std::to_string(domain), "--localhost-only"});
  EXPECT_EQ(saved.exit_code, 1) << saved.err;
  EXPECT_THAT(saved.err, Not(HasSubstr("\r")));
  std::vector<std::string> progress;
  std::istringstream lines(saved.err);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("waiting for the fused map") != std::string::npos) progress.push_back(line);
  }
  const std::string waiting = "waiting for the fused map on rt/fleetmap/map \\(DDS domain " +
                              std::to_string(domain) + "\\): ";
  ASSERT_EQ(progress.size(), 2u) << saved.err;
  EXPECT_THAT(progress[0], MatchesRegex(waiting + "0 / 3 s"));
  EXPECT_THAT(progress[1], MatchesRegex(waiting + "[0-9]+ / 3 s"));
  EXPECT_THAT(saved.err, HasSubstr(" / 3 s\nfleetmap save-map: no fused map"));
  std::filesystem::remove_all(out);
}

TEST(CliSaveMapTest, AnUnwritablePathIsRefusedBeforeWaiting) {
  const auto saved = testing::RunFleetmap(
      {"save-map", "-o", "/nonexistent-folder/fused.yaml", "--timeout", "60", "--localhost-only"},
      seconds(20));
  EXPECT_EQ(saved.exit_code, 2);
  EXPECT_THAT(saved.err, HasSubstr("/nonexistent-folder"));
  EXPECT_THAT(saved.err, HasSubstr("does not exist"));
}

}  // namespace
}  // namespace fleetmap
