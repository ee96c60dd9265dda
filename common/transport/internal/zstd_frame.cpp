#include "common/transport/internal/zstd_frame.hpp"

#include <zstd.h>

#include <memory>

namespace fleetmap::transport {
namespace {

struct ContextDeleter {
  void operator()(ZSTD_CCtx* context) const { ZSTD_freeCCtx(context); }
  void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
};

// One context per thread, reused: a context's set-up costs more than a small tile's compression.
ZSTD_CCtx* CompressionContext() {
  thread_local std::unique_ptr<ZSTD_CCtx, ContextDeleter> context(ZSTD_createCCtx());
  return context.get();
}

ZSTD_DCtx* DecompressionContext() {
  thread_local std::unique_ptr<ZSTD_DCtx, ContextDeleter> context(ZSTD_createDCtx());
  return context.get();
}

}  // namespace

std::vector<uint8_t> ZstdCompress(std::span<const uint8_t> bytes, int level) {
  std::vector<uint8_t> frame(ZSTD_compressBound(bytes.size()));
  const size_t size = ZSTD_compressCCtx(CompressionContext(), frame.data(), frame.size(),
                                        bytes.data(), bytes.size(), level);
  // Compressing into a buffer of ZSTD_compressBound bytes cannot fail.
  frame.resize(ZSTD_isError(size) ? 0 : size);
  return frame;
}

StatusOr<std::vector<uint8_t>> ZstdDecompress(std::span<const uint8_t> frame, size_t max_bytes,
                                              const std::string& what) {
  const unsigned long long declared = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) {
    return InvalidArgumentError(what + " is not a zstd frame");
  }
  if (declared == ZSTD_CONTENTSIZE_UNKNOWN) {
    return InvalidArgumentError(what + " is a zstd frame that does not record its content size");
  }
  if (declared > max_bytes) {
    return ResourceExhaustedError(what + " would decompress to " + std::to_string(declared) +
                                  " bytes, more than the " + std::to_string(max_bytes) +
                                  " allowed");
  }
  std::vector<uint8_t> bytes(static_cast<size_t>(declared));
  const size_t size = ZSTD_decompressDCtx(DecompressionContext(), bytes.data(), bytes.size(),
                                          frame.data(), frame.size());
  if (ZSTD_isError(size)) {
    return InvalidArgumentError(what + ": zstd: " + ZSTD_getErrorName(size));
  }
  if (size != bytes.size()) {
    return InvalidArgumentError(what + " decompressed to " + std::to_string(size) +
                                " bytes, not the " + std::to_string(bytes.size()) + " it states");
  }
  return bytes;
}

}  // namespace fleetmap::transport
