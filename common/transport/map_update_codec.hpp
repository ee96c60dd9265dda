#pragma once

// The patch wire's compression: a map update (map_message.hpp) whose cells travel zstd-compressed,
// as fleetmap_msgs/msg/CompressedGridUpdate. Compression runs on the agent; decompression on the
// receiver's own thread (never a DDS listener's), bounded by what the receiver will accept.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"

namespace fleetmap::transport {

// CompressedGridUpdate's `compression` values.
inline constexpr uint8_t kZstdCompression = 1;

// A CompressedGridUpdate as plain data. `data` is the compressed cells; `raw_size` what they
// inflate to (width * height bytes, one int8 per cell).
struct CompressedMapUpdate {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
  uint8_t compression = kZstdCompression;
  uint32_t raw_size = 0;
  std::vector<uint8_t> data;
  Timestamp stamp;
  std::string frame_id = "map";
  size_t serialized_bytes = 0;  // payload size, set by readers
};

// zstd at `level` (1..19; a live agent affords 3). kInvalidArgument for a bad level or an update
// whose data is not width * height cells, or that is larger than a uint32 raw_size can say.
StatusOr<CompressedMapUpdate> CompressMapUpdate(const MapUpdate& update, int level);

// Inflates `update`, allocating at most `max_cells` bytes: a receiver passes the cells of the map
// the update would patch. Refused (kInvalidArgument / kDataLoss, saying what is wrong): another
// compression than zstd; a raw_size that is not width * height or is above `max_cells`; a zstd
// frame that does not record its size, records another size, or does not decompress to exactly
// raw_size bytes; a cell outside -1..100.
StatusOr<MapUpdate> DecompressMapUpdate(const CompressedMapUpdate& update, size_t max_cells);

}  // namespace fleetmap::transport
