#include "bench/extrapolation/bench_extrapolation_command.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/inputs/exit_codes.hpp"
#include "common/grid/map_io.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::bench {
namespace {

// Two 4 m x 3 m rooms joined by a 0.9 m doorway: each is a room behind one door.
grid::OccupancyGrid TwoRooms() {
  grid::OccupancyGrid map(168, 64, 0.05, Pose2{0.0, 0.0, 0.0}, grid::kOccupiedValue);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Point2 c = map.CellCenter(x, y);
      const bool in_rows = c.y() > 0.1 && c.y() < 3.1;
      const bool rooms = (c.x() > 0.1 && c.x() < 4.1) || (c.x() > 4.25 && c.x() < 8.25);
      const bool doorway = c.x() >= 4.1 && c.x() <= 4.25 && c.y() > 1.0 && c.y() < 1.9;
      if ((in_rows && rooms) || doorway) map.at(x, y) = grid::kFreeValue;
    }
  }
  return map;
}

TEST(BenchExtrapolationCommandTest, RealMapsScoresEachHiddenRoomWithBothHinges) {
  const testing::ScratchDir dir("bench_real_maps");
  std::filesystem::create_directories(dir.Path("maps"));
  ASSERT_TRUE(grid::SaveMap(TwoRooms(), dir.Path("maps/two_rooms.yaml")).ok());
  BenchExtrapolationOptions options;
  options.real_maps_dir = dir.Path("maps");
  options.scenes = 0;
  options.out_dir = dir.Path("out");
  options.progress = false;
  std::ostringstream out, err;
  ASSERT_EQ(RunBenchExtrapolation(options, out, err), cli::kExitOk) << err.str();
  EXPECT_NE(out.str().find("| two_rooms | 2 | 2 |"), std::string::npos) << out.str();
  // One row per room (2), hinge choice (2) and threshold (3), after the header.
  const std::string csv = testing::ReadFile(dir.Path("out/real_maps.csv"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 2 * 3);
  const nlohmann::json json =
      nlohmann::json::parse(testing::ReadFile(dir.Path("out/real_maps.json")));
  ASSERT_EQ(json["thresholds"].size(), 3u);
  EXPECT_EQ(json["thresholds"][0]["doors"], 4);
  // The room behind the door is the whole prediction's target: something of it is predicted.
  EXPECT_EQ(json["thresholds"][0]["door_recall"], 1.0);
  EXPECT_EQ(json["thresholds"][0]["on_observed"], 0);
}

TEST(BenchExtrapolationCommandTest, RealMapsWithoutMapsIsBadInput) {
  const testing::ScratchDir dir("bench_real_maps");
  BenchExtrapolationOptions options;
  options.real_maps_dir = dir.Path("");
  options.scenes = 0;
  options.progress = false;
  std::ostringstream out, err;
  EXPECT_EQ(RunBenchExtrapolation(options, out, err), cli::kExitBadInput);
  EXPECT_NE(err.str().find("no map YAML files"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace fleetmap::bench
