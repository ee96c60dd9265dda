#include "common/fusion/tile_budget.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace fleetmap::fusion {
namespace {

double Mb(uint64_t bytes) { return static_cast<double>(bytes) / (1 << 20); }

std::string TileName(const TileId& tile) { return fmt::format("tile ({}, {})", tile.x, tile.y); }

}  // namespace

size_t BudgetOptions::MaxGeometryBytes() const {
  // An honest vertex takes 2 to 6 bytes (two varint steps); a polyline or ring adds its count
  // and half width. Twelve bytes a vertex and four a ring leave room for any honest lattice.
  return 64 + 12 * max_vertices_per_tile + 4 * max_rings_per_tile;
}

Status BudgetOptions::Validate() const {
  if (max_vertices_per_tile == 0 || max_rings_per_tile == 0 || max_vertices_per_robot == 0) {
    return InvalidArgumentError("the vertex and ring limits must be >= 1");
  }
  if (!(max_painted_tiles_per_tile > 0.0) || !(max_painted_tiles_per_robot > 0.0) ||
      !(max_painted_tiles_per_second > 0.0) || !(burst_painted_tiles > 0.0)) {
    return InvalidArgumentError("the painted-cell limits and rate must be positive");
  }
  if (!(robots_per_participant >= 1.0) || !(robots_per_host >= robots_per_participant)) {
    return InvalidArgumentError(
        "robots_per_participant must be >= 1 and robots_per_host >= robots_per_participant");
  }
  if (max_bytes_per_robot == 0 || max_memory_bytes < max_bytes_per_robot) {
    return InvalidArgumentError("max_memory_bytes must be >= max_bytes_per_robot > 0");
  }
  return Status::Ok();
}

void BudgetOptions::Describe(OptionsPrinter& out) const {
  out.Add("max_vertices_per_tile", max_vertices_per_tile);
  out.Add("max_rings_per_tile", max_rings_per_tile);
  out.Add("max_painted_tiles_per_tile", max_painted_tiles_per_tile);
  out.Add("max_vertices_per_robot", max_vertices_per_robot);
  out.Add("max_painted_tiles_per_robot", max_painted_tiles_per_robot);
  out.Add("max_bytes_per_robot", max_bytes_per_robot);
  out.Add("max_painted_tiles_per_second", max_painted_tiles_per_second);
  out.Add("burst_painted_tiles", burst_painted_tiles);
  out.Add("robots_per_participant", robots_per_participant);
  out.Add("robots_per_host", robots_per_host);
  out.Add("max_memory_bytes", max_memory_bytes);
}

TileBudget::TileBudget(const BudgetOptions& options, const fusion::FusionOptions& fusion)
    : options_(options), cells_per_tile_(CellsPerTile(fusion)) {}

std::optional<TileBudget::Refused> TileBudget::CheckTile(const TileId& tile,
                                                         const TileCost& cost) const {
  if (cost.vertices > options_.max_vertices_per_tile) {
    return Refused{Refusal::kDecodedSize,
                   fmt::format("{} has {} vertices; a tile may have {}", TileName(tile),
                               cost.vertices, options_.max_vertices_per_tile)};
  }
  if (cost.rings > options_.max_rings_per_tile) {
    return Refused{Refusal::kDecodedSize,
                   fmt::format("{} has {} free rings; a tile may have {}", TileName(tile),
                               cost.rings, options_.max_rings_per_tile)};
  }
  const double painted = static_cast<double>(cost.cells) / static_cast<double>(cells_per_tile_);
  if (painted > options_.max_painted_tiles_per_tile) {
    return Refused{
        Refusal::kDecodedSize,
        fmt::format("{} paints {} cells, {:.1f} tiles' worth; a tile may paint {}", TileName(tile),
                    cost.cells, painted, options_.max_painted_tiles_per_tile)};
  }
  return std::nullopt;
}

TileBudget::Robot& TileBudget::RobotOf(const Source& source) {
  auto [it, inserted] = robots_.try_emplace(source.robot);
  Robot& robot = it->second;
  if (inserted || robot.order == 0) robot.order = next_order_++;
  // Its first source stays its payer: a robot id has one owner (RobotRegistry).
  if (robot.participant.empty()) robot.participant = source.participant;
  if (robot.host.empty() && !source.host.empty()) {
    robot.host = source.host;
    host_bytes_[robot.host] += robot.total.bytes;
  }
  return robot;
}

std::optional<TileBudget::Refused> TileBudget::CheckRate(
    const Source& source, double painted_tiles, std::chrono::steady_clock::time_point now) {
  const std::string key =
      source.participant.empty() ? "robot " + source.robot.value : source.participant;
  auto [it, inserted] = rates_.try_emplace(key);
  Rate& rate = it->second;
  if (inserted) {
    rate.tokens = options_.burst_painted_tiles;
  } else {
    const double elapsed =
        std::max(0.0, std::chrono::duration<double>(now - rate.refilled).count());
    rate.tokens = std::min(options_.burst_painted_tiles,
                           rate.tokens + elapsed * options_.max_painted_tiles_per_second);
  }
  rate.refilled = now;
  if (painted_tiles > rate.tokens) {
    return Refused{
        Refusal::kPaintRate,
        fmt::format("participant {} asks to paint more than {:.0f} tiles' worth of "
                    "cells a second (burst {:.0f}) for its robots",
                    source.participant.empty() ? "(unknown)" : source.participant,
                    options_.max_painted_tiles_per_second, options_.burst_painted_tiles)};
  }
  rate.tokens -= painted_tiles;
  return std::nullopt;
}

std::optional<std::vector<RobotId>> TileBudget::NewerToEvict(const Robot& robot,
                                                             uint64_t extra) const {
  std::vector<std::pair<uint64_t, const RobotId*>> newer;
  for (const auto& [id, other] : robots_) {
    if (other.order > robot.order && other.total.bytes > 0) newer.emplace_back(other.order, &id);
  }
  std::sort(newer.begin(), newer.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  // The shared memory stays as it is: what evicting a robot frees of it is not known here.
  uint64_t total = held_bytes() + extra;
  std::vector<RobotId> evict;
  for (const auto& [order, id] : newer) {
    if (total <= options_.max_memory_bytes) break;
    total -= std::min(total, robots_.at(*id).total.bytes);
    evict.push_back(*id);
  }
  if (total > options_.max_memory_bytes) return std::nullopt;
  return evict;
}

std::variant<TileBudget::Charged, TileBudget::Refused> TileBudget::Charge(
    const Source& source, const TileId& tile, const TileCost& cost,
    std::chrono::steady_clock::time_point now) {
  if (auto refused = CheckTile(tile, cost)) return *refused;
  Robot& robot = RobotOf(source);
  const auto old = robot.tiles.find(tile);
  const TileCost before = old == robot.tiles.end() ? TileCost{} : old->second;
  TileCost after = robot.total;
  after -= before;
  after += cost;
  const uint64_t added = cost.bytes > before.bytes ? cost.bytes - before.bytes : 0;
  const std::string& who = source.robot.value;
  if (after.vertices > options_.max_vertices_per_robot) {
    return Refused{
        Refusal::kDecodedSize,
        fmt::format("{} would bring robot {} to {} vertices; a robot may hold {}", TileName(tile),
                    who, after.vertices, options_.max_vertices_per_robot)};
  }
  const double painted = static_cast<double>(after.cells) / static_cast<double>(cells_per_tile_);
  if (painted > options_.max_painted_tiles_per_robot) {
    return Refused{Refusal::kDecodedSize,
                   fmt::format("{} would bring robot {} to {:.0f} tiles' worth of painted "
                               "cells; a robot may paint {:.0f}",
                               TileName(tile), who, painted, options_.max_painted_tiles_per_robot)};
  }
  if (after.bytes > options_.max_bytes_per_robot) {
    return Refused{
        Refusal::kMemoryBudget,
        fmt::format("{} would bring robot {} to {:.0f} MB; a robot may hold {:.0f} MB",
                    TileName(tile), who, Mb(after.bytes), Mb(options_.max_bytes_per_robot))};
  }
  const auto share = [&](double robots) {
    return static_cast<uint64_t>(robots * static_cast<double>(options_.max_bytes_per_robot));
  };
  if (!robot.participant.empty() &&
      participant_bytes_[robot.participant] + added > share(options_.robots_per_participant)) {
    return Refused{Refusal::kMemoryBudget,
                   fmt::format("{} of robot {} would bring participant {} (all the robot ids it "
                               "speaks for) past {:.0f} MB",
                               TileName(tile), who, robot.participant,
                               Mb(share(options_.robots_per_participant)))};
  }
  if (!robot.host.empty() && host_bytes_[robot.host] + added > share(options_.robots_per_host)) {
    return Refused{
        Refusal::kMemoryBudget,
        fmt::format("{} of robot {} would bring host {} (all its participants) past "
                    "{:.0f} MB",
                    TileName(tile), who, robot.host, Mb(share(options_.robots_per_host)))};
  }
  Charged charged;
  if (held_bytes() + added > options_.max_memory_bytes) {
    std::optional<std::vector<RobotId>> evict = NewerToEvict(robot, added);
    if (!evict) {
      return Refused{
          Refusal::kMemoryBudget,
          fmt::format("{} of robot {}: all robots' tiles hold {:.0f} MB of the "
                      "server's {:.0f} MB ({:.0f} MB of it for tiles robots share), and the "
                      "robots claimed after {} do not hold enough to make room",
                      TileName(tile), who, Mb(held_bytes()), Mb(options_.max_memory_bytes),
                      Mb(shared_bytes_), who)};
    }
    charged.evict = std::move(*evict);
  }
  // Every admitted tile is painted again by fusion: re-sending costs as much as sending.
  const double cells = static_cast<double>(cost.cells);
  if (auto refused = CheckRate(source, cells / static_cast<double>(cells_per_tile_), now)) {
    return *refused;
  }
  Release(source.robot, tile);
  Robot& payer = robots_.at(source.robot);
  payer.tiles[tile] = cost;
  payer.total += cost;
  total_ += cost;
  if (!payer.participant.empty()) participant_bytes_[payer.participant] += cost.bytes;
  if (!payer.host.empty()) host_bytes_[payer.host] += cost.bytes;
  return charged;
}

void TileBudget::Adopt(const RobotId& robot, const TileId& tile, const TileCost& cost) {
  Release(robot, tile);
  Robot& owner = RobotOf(Source{robot, {}, {}});
  owner.tiles[tile] = cost;
  owner.total += cost;
  total_ += cost;
}

void TileBudget::Release(const RobotId& robot, const TileId& tile) {
  const auto it = robots_.find(robot);
  if (it == robots_.end()) return;
  Robot& owner = it->second;
  const auto held = owner.tiles.find(tile);
  if (held == owner.tiles.end()) return;
  const TileCost cost = held->second;
  owner.tiles.erase(held);
  owner.total -= cost;
  total_ -= cost;
  const auto drop = [&](std::map<std::string, uint64_t>& by, const std::string& key) {
    if (key.empty()) return;
    const auto entry = by.find(key);
    if (entry == by.end()) return;
    entry->second -= std::min(entry->second, cost.bytes);
    if (entry->second == 0) by.erase(entry);
  };
  drop(participant_bytes_, owner.participant);
  drop(host_bytes_, owner.host);
}

void TileBudget::ReleaseRobot(const RobotId& robot) {
  for (const TileId& tile : TilesOf(robot)) Release(robot, tile);
  robots_.erase(robot);
}

std::vector<TileId> TileBudget::TilesOf(const RobotId& robot) const {
  std::vector<TileId> tiles;
  const auto it = robots_.find(robot);
  if (it == robots_.end()) return tiles;
  for (const auto& [tile, cost] : it->second.tiles) tiles.push_back(tile);
  return tiles;
}

TileCost TileBudget::robot_cost(const RobotId& robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() ? TileCost{} : it->second.total;
}

uint64_t TileBudget::participant_bytes(const std::string& participant) const {
  const auto it = participant_bytes_.find(participant);
  return it == participant_bytes_.end() ? 0 : it->second;
}

}  // namespace fleetmap::fusion
