#include "common/transport/map_message.hpp"

#include <cstring>

namespace fleetmap::transport {

Status ApplyMapUpdate(const MapUpdate& update, grid::OccupancyGrid* map) {
  const int64_t x_end = static_cast<int64_t>(update.x) + update.width;
  const int64_t y_end = static_cast<int64_t>(update.y) + update.height;
  if (update.x < 0 || update.y < 0 || update.width < 0 || update.height < 0 ||
      x_end > map->width() || y_end > map->height()) {
    return InvalidArgumentError(
        "map update [" + std::to_string(update.x) + ", " + std::to_string(x_end) + ") x [" +
        std::to_string(update.y) + ", " + std::to_string(y_end) + ") lies outside the " +
        std::to_string(map->width()) + " x " + std::to_string(map->height()) + " map");
  }
  for (int row = 0; row < update.height; ++row) {
    std::memcpy(&map->at(update.x, update.y + row),
                update.data.data() + static_cast<size_t>(row) * update.width,
                static_cast<size_t>(update.width));
  }
  return Status::Ok();
}

}  // namespace fleetmap::transport
