#include "cli/inputs/command_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <utility>
#include <vector>

#include "common/transport/vmap_file.hpp"

namespace fleetmap::cli {
namespace {

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

size_t DropAreaLessFreeRings(vector_map::TiledVectorMap* map) {
  size_t dropped = 0;
  for (auto& [id, tile] : map->tiles) {
    std::vector<vector_map::FreePolygon> kept;
    for (vector_map::FreePolygon& polygon : tile.free_space) {
      if (polygon.outer.size() < 3) {
        dropped += 1 + polygon.holes.size();
        continue;
      }
      const auto end = std::remove_if(polygon.holes.begin(), polygon.holes.end(),
                                      [](const auto& hole) { return hole.size() < 3; });
      dropped += static_cast<size_t>(polygon.holes.end() - end);
      polygon.holes.erase(end, polygon.holes.end());
      kept.push_back(std::move(polygon));
    }
    tile.free_space = std::move(kept);
  }
  return dropped;
}

}  // namespace

StatusOr<grid::LoadedMap> LoadGridInput(const std::string& yaml_path, int64_t max_cells) {
  grid::MapLoadOptions options;
  options.max_cells = max_cells;
  return grid::LoadMap(yaml_path, options);
}

StatusOr<vector_map::TiledVectorMap> ReadVmapInput(const std::string& path) {
  return transport::ReadVmapFile(path);
}

Status CheckPositiveFinite(const std::string& flag, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    char shown[32];
    std::snprintf(shown, sizeof(shown), "%g", value);
    return InvalidArgumentError(flag + " must be a finite number > 0, got " + shown);
  }
  return Status::Ok();
}

Status CheckAxisAligned(const std::string& yaml_path, const grid::OccupancyGrid& grid) {
  if (std::abs(NormalizeAngle(grid.origin().yaw)) > 1e-9) {
    return InvalidArgumentError(
        yaml_path + ": origin yaw is " + std::to_string(grid.origin().yaw) +
        " rad; a .vmap holds axis-aligned tiles, so maps with a rotated origin are refused");
  }
  return Status::Ok();
}

StatusOr<grid::OccupancyGrid> TileBoundsGrid(const vector_map::TiledVectorMap& map,
                                             const std::string& vmap_path, double resolution,
                                             int64_t max_cells) {
  if (map.tiles.empty()) {
    return InvalidArgumentError(vmap_path +
                                ": holds no tiles, so it has no geometry of its own (pass --like)");
  }
  FLEETMAP_RETURN_IF_ERROR(CheckPositiveFinite("resolution", resolution));
  int64_t min_x = std::numeric_limits<int64_t>::max();
  int64_t min_y = min_x;
  int64_t max_x = std::numeric_limits<int64_t>::min();
  int64_t max_y = max_x;
  for (const auto& [id, tile] : map.tiles) {
    min_x = std::min<int64_t>(min_x, id.x);
    min_y = std::min<int64_t>(min_y, id.y);
    max_x = std::max<int64_t>(max_x, id.x + int64_t{1});
    max_y = std::max<int64_t>(max_y, id.y + int64_t{1});
  }
  const double width_m = static_cast<double>(max_x - min_x) * map.tile_size;
  const double height_m = static_cast<double>(max_y - min_y) * map.tile_size;
  // Rounded so that 10 m at 0.05 m is 200 cells despite 10 / 0.05 = 199.99999999999997.
  const double width = std::ceil(width_m / resolution - 1e-6);
  const double height = std::ceil(height_m / resolution - 1e-6);
  if (!(width * height <= static_cast<double>(max_cells)) ||
      width > std::numeric_limits<int>::max() || height > std::numeric_limits<int>::max()) {
    return ResourceExhaustedError(vmap_path + ": its tiles span " + std::to_string(width_m) +
                                  " x " + std::to_string(height_m) + " m, more than the limit of " +
                                  std::to_string(max_cells) + " cells at " +
                                  std::to_string(resolution) + " m/cell (--max-cells)");
  }
  const Pose2 origin{static_cast<double>(min_x) * map.tile_size,
                     static_cast<double>(min_y) * map.tile_size, 0.0};
  return grid::OccupancyGrid(static_cast<int>(width), static_cast<int>(height), resolution, origin);
}

double ShortestDouble(float value) {
  char buffer[32];
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", digits, static_cast<double>(value));
    const double parsed = std::strtod(buffer, nullptr);
    if (static_cast<float>(parsed) == value) return parsed;
  }
  return value;
}

StatusOr<std::string> EncodeVmapBytes(vector_map::TiledVectorMap* map, size_t* dropped_free_rings) {
  *dropped_free_rings = 0;
  StatusOr<std::string> bytes = transport::EncodeVmap(*map);
  if (bytes.ok()) return bytes;
  *dropped_free_rings = DropAreaLessFreeRings(map);
  if (*dropped_free_rings == 0) return bytes.status();
  return transport::EncodeVmap(*map);
}

double StoredEpsilonBound(double stored_epsilon) {
  return static_cast<double>(
      std::nextafter(static_cast<float>(stored_epsilon), std::numeric_limits<float>::infinity()));
}

bool HasExtension(const std::string& path, const std::string& extension) {
  return path.size() >= extension.size() &&
         Lower(path.substr(path.size() - extension.size())) == Lower(extension);
}

}  // namespace fleetmap::cli
