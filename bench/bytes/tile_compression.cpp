#include "bench/bytes/tile_compression.hpp"

#include <lz4.h>
#include <zstd.h>

#include <string>

namespace fleetmap::bench {

StatusOr<std::vector<uint8_t>> CompressZstd(std::span<const uint8_t> bytes, int level) {
  if (level < 1 || level > ZSTD_maxCLevel()) {
    return InvalidArgumentError("zstd level " + std::to_string(level) + " is not in 1.." +
                                std::to_string(ZSTD_maxCLevel()));
  }
  std::vector<uint8_t> out(ZSTD_compressBound(bytes.size()));
  const size_t size = ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), level);
  if (ZSTD_isError(size)) return InternalError(std::string("zstd: ") + ZSTD_getErrorName(size));
  out.resize(size);
  return out;
}

StatusOr<std::vector<uint8_t>> CompressLz4(std::span<const uint8_t> bytes) {
  if (bytes.size() > static_cast<size_t>(LZ4_MAX_INPUT_SIZE)) {
    return InvalidArgumentError("lz4: " + std::to_string(bytes.size()) +
                                " bytes is more than one LZ4 block holds");
  }
  const int input_size = static_cast<int>(bytes.size());
  std::vector<uint8_t> out(LZ4_compressBound(input_size));
  const int size = LZ4_compress_default(reinterpret_cast<const char*>(bytes.data()),
                                        reinterpret_cast<char*>(out.data()), input_size,
                                        static_cast<int>(out.size()));
  if (size <= 0 && input_size > 0) return InternalError("lz4: compression failed");
  out.resize(static_cast<size_t>(size));
  return out;
}

}  // namespace fleetmap::bench
