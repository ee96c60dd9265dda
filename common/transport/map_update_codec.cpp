#include "common/transport/map_update_codec.hpp"

#include <zstd.h>

#include <limits>

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
  out.data.resize(ZSTD_compressBound(update.data.size()));
  const size_t size = ZSTD_compress(out.data.data(), out.data.size(), update.data.data(),
                                    update.data.size(), level);
  if (ZSTD_isError(size)) {
    return InternalError(std::string("zstd compression failed: ") + ZSTD_getErrorName(size));
  }
  out.data.resize(size);
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
  // The frame's own header must agree before anything is allocated for it.
  const unsigned long long content =
      ZSTD_getFrameContentSize(update.data.data(), update.data.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) {
    return DataLossError("data is not a zstd frame (" + std::to_string(update.data.size()) +
                         " bytes)");
  }
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) {
    return DataLossError("the zstd frame does not record its content size");
  }
  if (content != cells) {
    return DataLossError("the zstd frame holds " + std::to_string(content) + " bytes, not the " +
                         std::to_string(cells) + " of raw_size");
  }
  MapUpdate out;
  out.data.resize(cells);
  const size_t size =
      ZSTD_decompress(out.data.data(), out.data.size(), update.data.data(), update.data.size());
  if (ZSTD_isError(size)) {
    return DataLossError(std::string("zstd: ") + ZSTD_getErrorName(size));
  }
  if (size != cells) {
    return DataLossError("data decompresses to " + std::to_string(size) + " bytes, not " +
                         std::to_string(cells));
  }
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
