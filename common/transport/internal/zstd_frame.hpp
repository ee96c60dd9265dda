#pragma once

// One zstd frame, both ways, for byte strings inside DDS samples. Decompression trusts nothing:
// the frame must state its content size, which must be within the caller's limit, and must
// decompress to exactly that many bytes; anything else is an error naming `what`
// (kResourceExhausted when only the limit is exceeded).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::transport {

// A frame with its content size (zstd's one-shot API writes it), at `level` (1..19).
std::vector<uint8_t> ZstdCompress(std::span<const uint8_t> bytes, int level);
StatusOr<std::vector<uint8_t>> ZstdDecompress(std::span<const uint8_t> frame, size_t max_bytes,
                                              const std::string& what);

}  // namespace fleetmap::transport
