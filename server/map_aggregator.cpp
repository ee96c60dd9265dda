#include "server/map_aggregator.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "common/grid/tiling.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::server {

ShardGrids::ShardGrids(const ShardPlan& plan) {
  for (const ShardRegion& region : plan.regions()) names_.push_back(region.name);
}

Status ShardGrids::Update(const std::string& shard, grid::OccupancyGrid grid) {
  if (std::find(names_.begin(), names_.end(), shard) == names_.end()) {
    return InvalidArgumentError("shard " + shard + " is not in the shard plan");
  }
  grids_[shard] = std::move(grid);
  return Status::Ok();
}

StatusOr<grid::OccupancyGrid> ShardGrids::Joined(int64_t max_cells) const {
  // StitchTiles places each grid by its origin on the first grid's cell lattice; the keys only
  // order them (the plan's order).
  grid::TileGrids parts;
  const grid::OccupancyGrid* first = nullptr;
  std::string first_name;
  for (size_t i = 0; i < names_.size(); ++i) {
    const auto it = grids_.find(names_[i]);
    if (it == grids_.end() || it->second.empty()) continue;
    const grid::OccupancyGrid& part = it->second;
    if (first == nullptr) {
      first = &part;
      first_name = names_[i];
    } else if (!grid::SameResolution(part.resolution(), first->resolution())) {
      return InvalidArgumentError(fmt::format(
          "shard {}'s grid has cells of {} m, shard {}'s of {} m: the shards must fuse at one "
          "--resolution",
          names_[i], part.resolution(), first_name, first->resolution()));
    }
    parts.emplace(TileId{static_cast<int32_t>(i), 0}, part);
  }
  StatusOr<grid::OccupancyGrid> joined = grid::StitchTiles(parts);
  if (!joined.ok()) {
    return InvalidArgumentError(
        "the shards' grids do not lie on one cell lattice (the shards "
        "must share --tile-size and --resolution): " +
        joined.status().message());
  }
  if (max_cells > 0 && joined->cell_count() > max_cells) {
    return ResourceExhaustedError(
        fmt::format("the shards' grids together span {} x {} cells, more than --max-map-cells {}: "
                    "rt/fleetmap/fused_tiles carries them all",
                    joined->width(), joined->height(), max_cells));
  }
  return joined;
}

std::vector<std::string> ShardGrids::Missing() const {
  std::vector<std::string> missing;
  for (const std::string& name : names_) {
    if (grids_.count(name) == 0) missing.push_back(name);
  }
  return missing;
}

StatusOr<std::unique_ptr<MapAggregator>> MapAggregator::Create(transport::Participant& participant,
                                                               const ShardPlan& plan,
                                                               const Options& options) {
  std::unique_ptr<MapAggregator> self(new MapAggregator(plan, options));
  for (const ShardRegion& region : plan.regions()) {
    FLEETMAP_ASSIGN_OR_RETURN(
        self->readers_[region.name],
        transport::OccupancyGridReader::Create(participant, transport::ShardMapTopic(region.name),
                                               self->wake_up_));
  }
  FLEETMAP_ASSIGN_OR_RETURN(self->writer_, transport::OccupancyGridWriter::Create(
                                               participant, transport::kFleetMapTopic));
  return self;
}

// The readers go before the participant that owns their topics (the caller's).
MapAggregator::~MapAggregator() = default;

Status MapAggregator::Run(const std::atomic<bool>& stop, std::chrono::milliseconds duration) {
  spdlog::info("aggregator: joining the grids of {} shard(s) into {}", readers_.size(),
               transport::kFleetMapTopic);
  const auto start = std::chrono::steady_clock::now();
  while (!stop.load()) {
    const auto now = std::chrono::steady_clock::now();
    if (duration.count() > 0 && now - start >= duration) break;
    Tick(now);
    wake_up_->WaitFor(std::chrono::milliseconds(100));
  }
  return Status::Ok();
}

void MapAggregator::Tick(std::chrono::steady_clock::time_point now) {
  for (auto& [shard, reader] : readers_) {
    for (StatusOr<transport::MapMessage>& message : reader->Drain()) {
      if (!message.ok()) {
        spdlog::warn("aggregator: {}: {}", reader->topic_name(), message.status().message());
        continue;
      }
      if (const Status updated = grids_.Update(shard, std::move(message->grid)); updated.ok()) {
        dirty_ = true;
      }
    }
  }
  if (!dirty_ || now - last_map_ < options_.map_period) return;
  StatusOr<grid::OccupancyGrid> joined = grids_.Joined(options_.max_grid_cells);
  if (!joined.ok()) {
    if (now - last_warning_ >= std::chrono::seconds(30)) {
      last_warning_ = now;
      spdlog::warn("aggregator: {}", joined.status().message());
    }
    dirty_ = false;  // until a shard's grid changes again
    return;
  }
  transport::MapMessage message;
  message.grid = std::move(joined).value();
  message.frame_id = "fleet";
  message.stamp = Clock::now();
  if (StatusOr<size_t> written = writer_->Write(message); !written.ok()) {
    spdlog::warn("aggregator: {}", written.status().message());
    return;
  }
  ++maps_published_;
  dirty_ = false;
  last_map_ = now;
}

}  // namespace fleetmap::server
