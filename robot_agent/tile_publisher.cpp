#include "robot_agent/tile_publisher.hpp"

#include <algorithm>
#include <cmath>

#include "common/grid/tiling.hpp"
#include "common/transport/tile_payload.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::agent {
namespace {

// Cells around a tile whose content its vectorization reads (border vertices, speck links).
constexpr int kContextCells = 3;
// The budget may bank this much time of unused bandwidth.
constexpr double kBurstSeconds = 2.0;
// A backlog worth more than this many seconds of budget coarsens epsilon.
constexpr double kBacklogSeconds = 5.0;
constexpr double kMaxEpsilonFactor = 4.0;
// What a disposal costs the budget: about a sample's key and header.
constexpr size_t kDisposeBytes = 64;

uint64_t Fnv1a(uint64_t hash, const void* data, size_t size) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

// The content a tile's vector map depends on: its cells and a thin ring around them, and where
// they are in the fleet frame (in whole cells, so a grid that grew keeps its old tiles' hashes).
uint64_t TileHash(const grid::OccupancyGrid& grid, const grid::CellRect& rect,
                  const Point2& fleet_corner) {
  const int x0 = std::max(0, rect.x0 - kContextCells);
  const int y0 = std::max(0, rect.y0 - kContextCells);
  const int x1 = std::min(grid.width(), rect.x0 + rect.width + kContextCells);
  const int y1 = std::min(grid.height(), rect.y0 + rect.height + kContextCells);
  const int64_t where[4] = {std::llround(fleet_corner.x() / grid.resolution()) + x0,
                            std::llround(fleet_corner.y() / grid.resolution()) + y0, x1 - x0,
                            y1 - y0};
  uint64_t hash = Fnv1a(0xcbf29ce484222325ULL, where, sizeof(where));
  for (int y = y0; y < y1; ++y) {
    hash = Fnv1a(hash, &grid.data()[static_cast<size_t>(y) * grid.width() + x0],
                 static_cast<size_t>(x1 - x0));
  }
  return hash;
}

}  // namespace

Status TilePublisherOptions::Validate() const {
  if (!std::isfinite(tile_size) || tile_size <= 0.0) {
    return InvalidArgumentError("--tile-size must be a positive number of metres");
  }
  if (!std::isfinite(epsilon) || epsilon < 0.0) {
    return InvalidArgumentError("--epsilon must be >= 0 metres (0: sqrt(2) * resolution)");
  }
  if (!std::isfinite(max_kbps) || max_kbps < 0.0) {
    return InvalidArgumentError("--max-kbps must be >= 0 (0: no budget)");
  }
  return Status::Ok();
}

StatusOr<std::unique_ptr<TilePublisher>> TilePublisher::Create(transport::Participant& participant,
                                                               RobotId robot, Pose2 fleet_from_map,
                                                               TilePublisherOptions options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<TilePublisher> publisher(
      new TilePublisher(std::move(robot), fleet_from_map, options));
  FLEETMAP_ASSIGN_OR_RETURN(publisher->writer_, transport::VectorTileWriter::Create(
                                                    participant, transport::kRobotTilesTopic));
  return publisher;
}

Status TilePublisher::Update(const grid::OccupancyGrid& grid) {
  const Transform2 fleet_from_map = fleet_from_map_.ToTransform();
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects,
                            grid::TileCellRects(grid, fleet_from_map, options_.tile_size));
  const Point2 fleet_corner = fleet_from_map * grid.origin().translation();

  vector_map::TiledVectorizeOptions vectorize;
  vectorize.tile_size = options_.tile_size;
  const double base_epsilon =
      options_.epsilon > 0.0 ? options_.epsilon : vector_map::DefaultEpsilon(grid.resolution());
  vectorize.vectorizer.epsilon = base_epsilon * epsilon_factor_;

  std::map<TileId, uint64_t> hashes;
  vector_map::TiledVectorMap scratch;
  for (const auto& [tile, rect] : rects) {
    const uint64_t hash = TileHash(grid, rect, fleet_corner);
    hashes[tile] = hash;
    const auto old = tile_hashes_.find(tile);
    if (old != tile_hashes_.end() && old->second == hash) continue;
    FLEETMAP_RETURN_IF_ERROR(
        vector_map::RevectorizeTile(grid, fleet_from_map, tile, vectorize, &scratch));
    const auto vectorized = scratch.tiles.find(tile);
    if (vectorized == scratch.tiles.end()) {
      // All unknown: nothing to say about this tile (any more).
      if (revisions_.count(tile) > 0) pending_[tile] = Pending{{}, true};
      continue;
    }
    pending_[tile] = Pending{std::move(vectorized->second), false};
    scratch.tiles.erase(vectorized);
  }
  for (const auto& [tile, hash] : tile_hashes_) {
    if (hashes.count(tile) == 0 && revisions_.count(tile) > 0) pending_[tile] = Pending{{}, true};
  }
  tile_hashes_ = std::move(hashes);
  return Status::Ok();
}

Status TilePublisher::Flush(std::chrono::steady_clock::time_point now) {
  const bool budgeted = options_.max_kbps > 0.0;
  const double bytes_per_second = options_.max_kbps * 1000.0 / 8.0;
  if (budgeted) {
    if (last_refill_ != std::chrono::steady_clock::time_point{}) {
      const double seconds = std::chrono::duration<double>(now - last_refill_).count();
      tokens_ = std::min(tokens_ + seconds * bytes_per_second, kBurstSeconds * bytes_per_second);
    } else {
      tokens_ = bytes_per_second;  // the first second's worth
    }
    last_refill_ = now;
  }

  size_t backlog = 0;
  for (auto it = pending_.begin(); it != pending_.end();) {
    const TileId tile = it->first;
    Pending& pending = it->second;
    transport::VectorTileMessage message;
    size_t estimate = kDisposeBytes;
    if (!pending.removed) {
      message.robot_id = robot_;
      message.tile = tile;
      message.revision = revisions_[tile] + 1;
      message.stamp = Clock::now();
      message.tile_size = options_.tile_size;
      message.map = std::move(pending.map);
      // The exact sample: the codec's varints and zstd make a formula a poor guess.
      FLEETMAP_ASSIGN_OR_RETURN(const std::string payload, transport::EncodeTilePayload(message));
      estimate = payload.size();
    }
    // Over budget: wait, unless the bucket is full and the tile alone is larger than it.
    if (budgeted && tokens_ < static_cast<double>(estimate) &&
        tokens_ < kBurstSeconds * bytes_per_second) {
      backlog += estimate;
      if (!pending.removed) pending.map = std::move(message.map);
      ++it;
      continue;
    }
    size_t bytes = 0;
    if (pending.removed) {
      FLEETMAP_RETURN_IF_ERROR(writer_->Dispose(robot_, tile));
      revisions_.erase(tile);
      bytes = estimate;
    } else {
      FLEETMAP_ASSIGN_OR_RETURN(bytes, writer_->Write(message));
      revisions_[tile] = message.revision;
      ++tiles_published_;
    }
    bytes_published_ += bytes;
    tokens_ -= static_cast<double>(bytes);
    it = pending_.erase(it);
  }

  // A lasting backlog means the map changes faster than the budget carries it: coarser epsilon
  // for the next re-vectorizations; back to the requested epsilon once the backlog is gone.
  if (budgeted && static_cast<double>(backlog) > kBacklogSeconds * bytes_per_second) {
    epsilon_factor_ = std::min(kMaxEpsilonFactor, epsilon_factor_ * 2.0);
  } else if (pending_.empty()) {
    epsilon_factor_ = 1.0;
  }
  return Status::Ok();
}

void TilePublisherOptions::Describe(OptionsPrinter& out) const {
  out.Add("tile_size", tile_size);
  out.Add("epsilon", epsilon);
  out.Add("max_kbps", max_kbps);
}

}  // namespace fleetmap::agent
