#include "robot_agent/map_source.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "common/process/subprocess.hpp"
#include "common/transport/checked_type_support.hpp"
#include "common/transport/conversions.hpp"
#include "common/transport/endpoint.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/qos.hpp"

namespace fleetmap::agent {
namespace {

using std::chrono::milliseconds;

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
  auto update_writer = transport::WriterEndpoint::Create(
      **slam, "rt/map_updates", transport::OccupancyGridUpdateTypeSupport(),
      transport::OccupancyGridUpdateQos().writer);
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
  auto outside_sample = transport::ToIdl(outside);
  auto inside_sample = transport::ToIdl(inside);
  const auto patched = [](const grid::OccupancyGrid& g) {
    return g.at(3, 1) == grid::kOccupiedValue && g.at(4, 2) == grid::kOccupiedValue;
  };
  std::optional<grid::OccupancyGrid> updated;
  for (int attempt = 0; attempt < 100 && !(updated && patched(*updated)); ++attempt) {
    (*update_writer)->writer()->write(&outside_sample);
    (*update_writer)->writer()->write(&inside_sample);
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
