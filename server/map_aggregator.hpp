#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::server {

// The shards' grids joined into one (DDS-free): each shard's grid covers its own region's fused
// tiles, so the joined grid is the smallest that holds them all, unknown where no shard has a
// tile: the grid one server fusing every region would publish (docs/shards.md).
class ShardGrids {
 public:
  explicit ShardGrids(const ShardPlan& plan);

  // The shard's newest grid (a shard not in the plan is refused, naming it).
  Status Update(const std::string& shard, grid::OccupancyGrid grid);
  // The joined grid; an error names the shard whose grid does not fit the others (another
  // resolution or cell lattice), or says the whole is over `max_cells`.
  StatusOr<grid::OccupancyGrid> Joined(int64_t max_cells) const;
  // Shards of the plan that have not published a grid yet.
  std::vector<std::string> Missing() const;

 private:
  std::vector<std::string> names_;  // in the plan's order
  std::map<std::string, grid::OccupancyGrid> grids_;
};

// `fleetmap-server --aggregate`: reads every shard's rt/fleetmap/<shard>/map and writes the joined
// grid on rt/fleetmap/map, what Nav2 and RViz read, at most once a map period and only when a
// shard's grid changed.
class MapAggregator {
 public:
  struct Options {
    std::chrono::milliseconds map_period{1000};
    int64_t max_grid_cells = 0;
  };
  static StatusOr<std::unique_ptr<MapAggregator>> Create(transport::Participant& participant,
                                                         const ShardPlan& plan,
                                                         const Options& options);
  ~MapAggregator();

  // Runs until `stop` (or `duration`, when not zero).
  Status Run(const std::atomic<bool>& stop, std::chrono::milliseconds duration);

  uint64_t maps_published() const { return maps_published_; }

 private:
  MapAggregator(const ShardPlan& plan, const Options& options) : options_(options), grids_(plan) {}
  // Takes what the shards wrote; writes the joined grid when due.
  void Tick(std::chrono::steady_clock::time_point now);

  Options options_;
  ShardGrids grids_;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::map<std::string, std::unique_ptr<transport::OccupancyGridReader>> readers_;  // by shard
  std::unique_ptr<transport::OccupancyGridWriter> writer_;
  bool dirty_ = false;
  std::chrono::steady_clock::time_point last_map_{};
  std::chrono::steady_clock::time_point last_warning_{};
  uint64_t maps_published_ = 0;
};

}  // namespace fleetmap::server
