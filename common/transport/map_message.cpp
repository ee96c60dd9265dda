#include "common/transport/map_message.hpp"

#include <cstring>

namespace fleetmap::transport {

Status CheckUpdateRectangle(int x, int y, int width, int height, int map_width, int map_height) {
  const int64_t x_end = static_cast<int64_t>(x) + width;
  const int64_t y_end = static_cast<int64_t>(y) + height;
  if (x < 0 || y < 0 || width < 0 || height < 0 || x_end > map_width || y_end > map_height) {
    return InvalidArgumentError("map update [" + std::to_string(x) + ", " + std::to_string(x_end) +
                                ") x [" + std::to_string(y) + ", " + std::to_string(y_end) +
                                ") lies outside the " + std::to_string(map_width) + " x " +
                                std::to_string(map_height) + " map");
  }
  return Status::Ok();
}

Status ApplyMapUpdate(const MapUpdate& update, grid::OccupancyGrid* map) {
  FLEETMAP_RETURN_IF_ERROR(CheckUpdateRectangle(update.x, update.y, update.width, update.height,
                                                map->width(), map->height()));
  if (update.data.size() != static_cast<size_t>(update.width) * update.height) {
    return InvalidArgumentError("map update of " + std::to_string(update.width) + " x " +
                                std::to_string(update.height) + " cells carries " +
                                std::to_string(update.data.size()));
  }
  for (int row = 0; row < update.height; ++row) {
    std::memcpy(&map->at(update.x, update.y + row),
                update.data.data() + static_cast<size_t>(row) * update.width,
                static_cast<size_t>(update.width));
  }
  return Status::Ok();
}

}  // namespace fleetmap::transport
