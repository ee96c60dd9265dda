#include "bench/fleet/hostile_flood.hpp"

#include <chrono>
#include <cmath>
#include <random>

#include "common/transport/topics.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::bench {
namespace {

constexpr double kTileSize = 10.0;

// A tile of `walls` short random walls on free space: costly to rasterize and to vectorize again.
vector_map::VectorMap HeavyTile(const TileId& tile, int walls, std::mt19937* random) {
  vector_map::VectorMap map;
  map.frame_id = "fleet";
  map.epsilon = 0.07;
  map.resolution = 0.05;
  const double quantum = vector_map::TileQuantum(map.resolution);
  map.lattice = {quantum, Point2::Zero()};
  const double x0 = tile.x * kTileSize;
  const double y0 = tile.y * kTileSize;
  // Vertices on the tile lattice, as an agent's would be.
  const auto lattice = [&](double v) { return std::round(v / quantum) * quantum; };
  std::uniform_real_distribution<double> along(0.2, kTileSize - 0.2);
  std::uniform_real_distribution<double> step(-0.3, 0.3);
  for (int i = 0; i < walls; ++i) {
    vector_map::Polyline wall;
    const double x = along(*random);
    const double y = along(*random);
    wall.points = {{lattice(x0 + x), lattice(y0 + y)},
                   {lattice(x0 + x + step(*random)), lattice(y0 + y + step(*random))}};
    map.obstacles.push_back(std::move(wall));
  }
  map.free_space.push_back(
      vector_map::FreePolygon{{{x0, y0},
                               {x0 + kTileSize - quantum, y0},
                               {x0 + kTileSize - quantum, y0 + kTileSize - quantum},
                               {x0, y0 + kTileSize - quantum}},
                              {}});
  return map;
}

}  // namespace

StatusOr<std::unique_ptr<HostileFlood>> HostileFlood::Create(transport::ParticipantOptions dds,
                                                             const HostileFloodOptions& options) {
  std::unique_ptr<HostileFlood> flood(new HostileFlood(options));
  dds.name = "fleetmap-bench-hostile";
  FLEETMAP_ASSIGN_OR_RETURN(flood->participant_, transport::Participant::Create(dds));
  FLEETMAP_ASSIGN_OR_RETURN(flood->status_,
                            transport::RobotStatusWriter::Create(*flood->participant_));
  FLEETMAP_ASSIGN_OR_RETURN(flood->tiles_, transport::VectorTileWriter::Create(
                                               *flood->participant_, transport::kRobotTilesTopic));
  return flood;
}

HostileFlood::~HostileFlood() {
  Stop();
  tiles_.reset();
  status_.reset();
}

void HostileFlood::Start() {
  thread_ = std::thread([this] { Run(); });
}

void HostileFlood::Stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

std::vector<RobotId> HostileFlood::robot_ids() const {
  if (options_.ids <= 1) return {RobotId{options_.robot}};
  std::vector<RobotId> ids;
  for (int i = 0; i < options_.ids; ++i) {
    std::string name = options_.robot;
    name += "_";
    name += std::to_string(i);
    ids.push_back(RobotId{std::move(name)});
  }
  return ids;
}

void HostileFlood::Run() {
  std::mt19937 random(7);
  const std::vector<RobotId> ids = robot_ids();
  std::vector<RobotStatus> statuses(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    statuses[i].robot = ids[i];
    statuses[i].map_topic = transport::kRobotTilesTopic;
  }
  uint32_t revision = 0;
  const auto write = [&](const RobotId& robot, const TileId& tile, int walls) {
    transport::VectorTileMessage message;
    message.robot_id = robot;
    message.tile = tile;
    message.revision = ++revision;
    message.stamp = Clock::now();
    message.tile_size = kTileSize;
    message.map = HeavyTile(tile, walls, &random);
    if (tiles_->Write(message).ok()) ++tiles_written_;
  };
  // Every id's claim, renewed about once a second (a status per id is part of the load).
  auto next_claim = std::chrono::steady_clock::time_point{};
  const auto keep_alive = [&] {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_claim) return;
    next_claim = now + std::chrono::seconds(1);
    for (RobotStatus& status : statuses) {
      status.stamp = Clock::now();
      ++status.sequence_number;
      (void)status_->Write(status);
    }
  };
  keep_alive();
  // Give the server time to see the claims, as a peer that knows the protocol would.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto heavy_round = [&] {
    keep_alive();
    for (int i = 0; i < options_.heavy_tiles; ++i) {
      write(ids.front(), TileId{options_.first_tile_x + i % 8, i / 8}, 300);
    }
  };
  // The heavy tiles first, so that they hold places in the first id's tile quota and are fused
  // for the whole run; then the distinct keys, spread over the ids, which run into the quotas
  // and budgets.
  heavy_round();
  const int side = 64;
  for (int k = 0; k < options_.distinct_keys && !stop_.load(); ++k) {
    write(ids[k % ids.size()], TileId{options_.first_tile_x + 100 + k % side, k / side}, 4);
    if (k % 100 == 0) keep_alive();
  }
  const auto period = std::chrono::duration<double>(1.0 / options_.rate_hz);
  auto next = std::chrono::steady_clock::now();
  while (!stop_.load()) {
    heavy_round();
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
    std::this_thread::sleep_until(next);
  }
  (void)status_->Leave(ids);
}

}  // namespace fleetmap::bench
