#include "common/transport/map_update_codec.hpp"

#include <zstd.h>

#include <limits>

#include "common/transport/internal/zstd_frame.hpp"

namespace fleetmap::transport {

StatusOr<CompressedMapUpdate> CompressMapUpdate(const MapUpdate& update, int level) {
  if (level < 1 || level > ZSTD_maxCLevel()) {
    return InvalidArgumentError("zstd level " + std::to_string(level) + " is not in 1.." +
                                std::to_string(ZSTD_maxCLevel()));
  }
  const uint64_t cells = static_cast<uint64_t>(update.width) * static_cast<uint64_t>(update.height);
  if (update.width < 0 || update.height < 0 || cells != update.data.size()) {
    return InvalidArgumentError("map update of " + std::to_string(update.width) + " x " +
                                std::to_string(update.height) + " cells carries " +
                                std::to_string(update.data.size()));
  }
  if (cells > std::numeric_limits<uint32_t>::max()) {
    return InvalidArgumentError("map update of " + std::to_string(cells) +
                                " cells is too large for a CompressedGridUpdate");
  }
  CompressedMapUpdate out;
  out.x = update.x;
  out.y = update.y;
  out.width = update.width;
  out.height = update.height;
  out.compression = kZstdCompression;
  out.raw_size = static_cast<uint32_t>(cells);
  out.stamp = update.stamp;
  out.frame_id = update.frame_id;
  out.data = ZstdCompress(
      {reinterpret_cast<const uint8_t*>(update.data.data()), update.data.size()}, level);
  if (out.data.empty()) return InternalError("zstd compression failed");
  return out;
}

StatusOr<MapUpdate> DecompressMapUpdate(const CompressedMapUpdate& update, size_t max_cells) {
  if (update.compression != kZstdCompression) {
    return InvalidArgumentError("compression " + std::to_string(update.compression) +
                                " is not zstd (1), the only one defined");
  }
  if (update.width < 0 || update.height < 0) {
    return InvalidArgumentError("a negative rectangle (" + std::to_string(update.width) + " x " +
                                std::to_string(update.height) + ")");
  }
  const uint64_t cells = static_cast<uint64_t>(update.width) * static_cast<uint64_t>(update.height);
  if (update.raw_size != cells) {
    return InvalidArgumentError(
        "raw_size " + std::to_string(update.raw_size) + " is not " + std::to_string(update.width) +
        " x " + std::to_string(update.height) + " = " + std::to_string(cells) + " cells");
  }
  if (cells > max_cells) {
    return InvalidArgumentError("raw_size " + std::to_string(update.raw_size) +
                                " is more than the " + std::to_string(max_cells) +
                                " cells accepted");
  }
  // The frame's own header must agree before anything is allocated for it (ZstdDecompress checks
  // it against `cells`).
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> cells_data,
                            ZstdDecompress(update.data, cells, "data"));
  if (cells_data.size() != cells) {
    return DataLossError("the zstd frame holds " + std::to_string(cells_data.size()) +
                         " bytes, not the " + std::to_string(cells) + " of raw_size");
  }
  MapUpdate out;
  out.data.assign(cells_data.begin(), cells_data.end());
  for (const int8_t value : out.data) {
    if (value < -1 || value > 100) {
      return InvalidArgumentError("a cell value " + std::to_string(value) + " outside -1..100");
    }
  }
  out.x = update.x;
  out.y = update.y;
  out.width = update.width;
  out.height = update.height;
  out.stamp = update.stamp;
  out.frame_id = update.frame_id;
  out.serialized_bytes = update.serialized_bytes;
  return out;
}

}  // namespace fleetmap::transport
