#include "common/fusion/tile_admission.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fleetmap::fusion {
namespace {

std::string TileName(const vector_map::VectorTile& tile) {
  return fmt::format("tile ({}, {})", tile.tile.x, tile.tile.y);
}

double Seconds(std::chrono::nanoseconds duration) {
  return std::chrono::duration<double>(duration).count();
}

}  // namespace

Status AdmissionOptions::Validate() const {
  if (max_clock_ahead.count() < 0) return InvalidArgumentError("max_clock_ahead must be >= 0");
  if (max_age.count() <= 0) return InvalidArgumentError("max_age must be positive");
  if (max_tiles_per_robot == 0) return InvalidArgumentError("max_tiles_per_robot must be >= 1");
  if (!(max_bytes_per_second > 0.0) || !(burst_bytes > 0.0)) {
    return InvalidArgumentError("the byte quota and its burst must be positive");
  }
  return budget.Validate();
}

vector_map::TileDecodeLimits AdmissionOptions::DecodeLimits() const {
  vector_map::TileDecodeLimits limits;
  limits.max_geometry_bytes = budget.MaxGeometryBytes();
  limits.max_vertices = budget.max_vertices_per_tile;
  limits.max_rings = budget.max_rings_per_tile;
  return limits;
}

std::optional<TileAdmission::Refused> TileAdmission::CheckSettings(
    const vector_map::VectorTile& tile) const {
  const double tile_size = fusion_.tile_size;
  if (std::abs(tile.tile_size - tile_size) > 1e-9 * tile_size) {
    return Refused{Refusal::kBadTileSettings,
                   fmt::format("{} is cut in {} m tiles; this fleet's tiles are {} m",
                               TileName(tile), tile.tile_size, tile_size)};
  }
  // A tile's geometry is only meaningful at a small fraction of the tile: a larger error bound
  // or cell would let one tile paint arbitrary shapes.
  const double largest = tile_size / 8.0;
  if (!(tile.map.epsilon > 0.0 && tile.map.epsilon <= largest)) {
    return Refused{Refusal::kBadTileSettings,
                   fmt::format("{} has epsilon {} m; accepted: (0, {}] m", TileName(tile),
                               tile.map.epsilon, largest)};
  }
  if (!(tile.map.resolution >= 1e-3 && tile.map.resolution <= largest)) {
    return Refused{Refusal::kBadTileSettings,
                   fmt::format("{} has resolution {} m; accepted: [0.001, {}] m", TileName(tile),
                               tile.map.resolution, largest)};
  }
  if (const Status range = fusion_.CheckTileInRange(tile.tile); !range.ok()) {
    return Refused{Refusal::kTileOutOfRange, range.message()};
  }
  return std::nullopt;
}

std::optional<TileAdmission::Refused> TileAdmission::CheckStamp(const vector_map::VectorTile& tile,
                                                                Timestamp now) const {
  if (tile.stamp > now + options_.max_clock_ahead) {
    return Refused{
        Refusal::kStampOutOfWindow,
        fmt::format("{} is stamped {:.1f} s ahead of this server's clock (at most {:.1f} "
                    "s accepted): check the robot's clock",
                    TileName(tile), Seconds(tile.stamp - now), Seconds(options_.max_clock_ahead))};
  }
  if (tile.stamp < now - options_.max_age) {
    return Refused{
        Refusal::kStampOutOfWindow,
        fmt::format("{} is stamped {:.0f} s before this server's clock (at most {} h "
                    "accepted)",
                    TileName(tile), Seconds(now - tile.stamp), options_.max_age.count())};
  }
  return std::nullopt;
}

std::optional<TileAdmission::Refused> TileAdmission::CheckRobotId(
    const vector_map::VectorTile& tile) {
  if (IsValidRobotName(tile.robot_id.value) && tile.robot_id.value != kFleetRobotName)
    return std::nullopt;
  return Refused{Refusal::kBadRobotId,
                 fmt::format("robot_id \"{}\" of {} is not a ROS 2 name token of at most 64 "
                             "characters (or is the reserved \"{}\")",
                             tile.robot_id.value.substr(0, 64), TileName(tile), kFleetRobotName)};
}

TileAdmission::Verdict TileAdmission::Admit(const vector_map::VectorTile& tile, size_t bytes,
                                            Timestamp now,
                                            std::chrono::steady_clock::time_point steady_now) {
  return Admit(tile, bytes, TileBudget::Source{tile.robot_id, {}, {}}, now, steady_now);
}

TileAdmission::Verdict TileAdmission::Admit(const vector_map::VectorTile& tile, size_t bytes,
                                            const TileBudget::Source& source, Timestamp now,
                                            std::chrono::steady_clock::time_point steady_now) {
  if (auto refused = CheckRobotId(tile)) return *refused;
  if (auto refused = CheckSettings(tile)) return *refused;
  if (auto refused = CheckStamp(tile, now)) return *refused;

  RobotQuota& quota = robots_[tile.robot_id];
  if (quota.tiles.count(tile.tile) == 0 && quota.tiles.size() >= options_.max_tiles_per_robot) {
    return Refused{
        Refusal::kTileQuota,
        fmt::format("{} would be robot {}'s tile number {}; a robot may hold {}", TileName(tile),
                    tile.robot_id.value, quota.tiles.size() + 1, options_.max_tiles_per_robot)};
  }
  // Token bucket: refilled at the sustained rate, capped at the burst.
  if (!quota.started) {
    quota.byte_tokens = options_.burst_bytes;
    quota.started = true;
  } else {
    const double elapsed = Seconds(steady_now - quota.refilled);
    quota.byte_tokens =
        std::min(options_.burst_bytes,
                 quota.byte_tokens + std::max(0.0, elapsed) * options_.max_bytes_per_second);
  }
  quota.refilled = steady_now;
  if (static_cast<double>(bytes) > quota.byte_tokens) {
    return Refused{Refusal::kByteQuota,
                   fmt::format("{} of {} bytes exceeds robot {}'s byte quota ({:.0f} bytes/s, "
                               "burst {:.0f})",
                               TileName(tile), bytes, tile.robot_id.value,
                               options_.max_bytes_per_second, options_.burst_bytes)};
  }
  // What the tile costs decoded, against the robot's, its participant's, its host's and the
  // global budget: checked last, so that a refused tile is not charged.
  auto charged = budget_.Charge(source, tile.tile, CostOf(tile.map, fusion_), steady_now);
  if (auto* refused = std::get_if<TileBudget::Refused>(&charged)) {
    return Refused{refused->reason, std::move(refused->detail)};
  }
  quota.byte_tokens -= static_cast<double>(bytes);
  quota.tiles.insert(tile.tile);
  return Admitted{std::min(tile.stamp, now),
                  std::move(std::get<TileBudget::Charged>(charged).evict)};
}

std::vector<TileId> TileAdmission::DropRobot(const RobotId& robot) {
  std::vector<TileId> tiles = budget_.TilesOf(robot);
  budget_.ReleaseRobot(robot);
  const auto it = robots_.find(robot);
  if (it != robots_.end()) {
    for (const TileId& tile : it->second.tiles) {
      if (std::find(tiles.begin(), tiles.end(), tile) == tiles.end()) tiles.push_back(tile);
    }
    it->second.tiles.clear();
  }
  return tiles;
}

void TileAdmission::Adopt(const RobotId& robot, const TileId& tile) {
  robots_[robot].tiles.insert(tile);
  budget_.Adopt(robot, tile, CostOfUnknownTile(fusion_));
}

void TileAdmission::Forget(const RobotId& robot, const TileId& tile) {
  const auto it = robots_.find(robot);
  if (it != robots_.end()) it->second.tiles.erase(tile);
  budget_.Release(robot, tile);
}

size_t TileAdmission::tiles_held(const RobotId& robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() ? 0 : it->second.tiles.size();
}

void AdmissionOptions::Describe(OptionsPrinter& out) const {
  out.Add("max_clock_ahead", max_clock_ahead);
  out.Add("max_age", max_age);
  out.Add("max_tiles_per_robot", max_tiles_per_robot);
  out.Add("max_bytes_per_second", max_bytes_per_second);
  out.Add("burst_bytes", burst_bytes);
  out.Nested("budget", budget);
}

}  // namespace fleetmap::fusion
