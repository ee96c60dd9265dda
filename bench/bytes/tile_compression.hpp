#pragma once

// The compressors of the grid baselines. Each call compresses its buffer alone (no dictionary,
// no state carried from one call to the next), as each tile travels alone on the wire.

#include <cstdint>
#include <span>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::bench {

// One zstd frame at `level` (1..19), as `zstd -<level>` writes it: the frame header (with the
// content size) is counted, as a receiver needs it.
StatusOr<std::vector<uint8_t>> CompressZstd(std::span<const uint8_t> bytes, int level);

// LZ4 block format at the default acceleration (LZ4_compress_default), no frame: a grid patch
// already says its width and height, so the decoded size is known without one. This favours the
// baseline by the 7-19 bytes an LZ4 frame header would add.
StatusOr<std::vector<uint8_t>> CompressLz4(std::span<const uint8_t> bytes);

}  // namespace fleetmap::bench
