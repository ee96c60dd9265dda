#include "common/core/shard_regions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap {
namespace {

// The first tile index whose centre (i + 0.5) * tile_size is at or past `x`.
int32_t FirstTileCentredFrom(double x, double tile_size) {
  const double index = std::ceil(x / tile_size - 0.5);
  return static_cast<int32_t>(std::clamp(index,
                                         static_cast<double>(std::numeric_limits<int32_t>::min()),
                                         static_cast<double>(std::numeric_limits<int32_t>::max())));
}

bool Overlap(const ShardRegion& a, const ShardRegion& b) {
  return a.min_x < b.max_x && b.min_x < a.max_x && a.min_y < b.max_y && b.min_y < a.max_y;
}

}  // namespace

TileBox ShardRegion::Tiles(double tile_size) const {
  // Half-open in metres, so two regions that share a border never both hold a tile's centre.
  return TileBox{FirstTileCentredFrom(min_x, tile_size), FirstTileCentredFrom(min_y, tile_size),
                 FirstTileCentredFrom(max_x, tile_size) - 1,
                 FirstTileCentredFrom(max_y, tile_size) - 1};
}

StatusOr<ShardPlan> ShardPlan::Create(std::vector<ShardRegion> regions,
                                      std::map<RobotId, std::string> homes) {
  if (regions.empty()) return InvalidArgumentError("a shard plan needs at least one shard");
  for (size_t i = 0; i < regions.size(); ++i) {
    const ShardRegion& region = regions[i];
    if (!IsValidRobotName(region.name)) {
      return InvalidArgumentError(fmt::format(
          "shard \"{}\": a shard name is a ROS 2 name token (a letter, then letters, digits and "
          "_; at most 64): its map is rt/fleetmap/<name>/map",
          region.name));
    }
    const double corners[] = {region.min_x, region.min_y, region.max_x, region.max_y};
    if (!std::all_of(std::begin(corners), std::end(corners),
                     [](double v) { return std::isfinite(v); })) {
      return InvalidArgumentError("shard " + region.name + ": its region is not finite");
    }
    if (!(region.min_x < region.max_x && region.min_y < region.max_y)) {
      return InvalidArgumentError(
          fmt::format("shard {}: region [{}, {}] x [{}, {}] has no area (X0 < X1 and Y0 < Y1)",
                      region.name, region.min_x, region.max_x, region.min_y, region.max_y));
    }
    for (size_t j = 0; j < i; ++j) {
      if (regions[j].name == region.name) {
        return InvalidArgumentError("shard " + region.name + " is listed twice");
      }
      if (Overlap(regions[j], region)) {
        return InvalidArgumentError(fmt::format(
            "shards {} and {} overlap: regions must not overlap (each tile has one shard)",
            regions[j].name, region.name));
      }
    }
  }
  for (const auto& home : homes) {
    // Named, not bound: clang does not let a lambda capture a structured binding.
    const std::string& robot = home.first.value;
    const std::string& shard = home.second;
    if (!IsValidRobotName(robot)) {
      return InvalidArgumentError("\"" + robot + "\" is not a valid robot name");
    }
    const bool listed = std::any_of(regions.begin(), regions.end(), [&](const ShardRegion& region) {
      return region.name == shard;
    });
    if (!listed) {
      return InvalidArgumentError("robot " + robot + " is homed on shard " + shard +
                                  ", which is not listed");
    }
  }
  ShardPlan plan;
  plan.regions_ = std::move(regions);
  plan.homes_ = std::move(homes);
  return plan;
}

const ShardRegion* ShardPlan::Find(const std::string& name) const {
  for (const ShardRegion& region : regions_) {
    if (region.name == name) return &region;
  }
  return nullptr;
}

const std::string& ShardPlan::HomeOf(const RobotId& robot) const {
  const auto home = homes_.find(robot);
  return home != homes_.end() ? home->second : regions_.front().name;
}

const ShardRegion* ShardPlan::OwnerOf(const TileId& tile, double tile_size) const {
  for (const ShardRegion& region : regions_) {
    if (region.Tiles(tile_size).Contains(tile)) return &region;
  }
  return nullptr;
}

}  // namespace fleetmap
