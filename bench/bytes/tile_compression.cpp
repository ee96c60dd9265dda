#include "bench/bytes/tile_compression.hpp"

#include <lz4.h>
#include <zdict.h>
#include <zstd.h>

#include <memory>
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

StatusOr<ZstdDictionary> ZstdDictionary::Train(const std::vector<std::vector<uint8_t>>& samples,
                                               size_t capacity) {
  std::vector<uint8_t> concatenated;
  std::vector<size_t> sizes;
  for (const std::vector<uint8_t>& sample : samples) {
    if (sample.empty()) continue;
    concatenated.insert(concatenated.end(), sample.begin(), sample.end());
    sizes.push_back(sample.size());
  }
  constexpr size_t kMinSamples = 8;
  if (sizes.size() < kMinSamples) {
    return InvalidArgumentError("a zstd dictionary needs at least " + std::to_string(kMinSamples) +
                                " samples to train on, got " + std::to_string(sizes.size()));
  }
  std::vector<uint8_t> dictionary(capacity);
  const size_t size =
      ZDICT_trainFromBuffer(dictionary.data(), dictionary.size(), concatenated.data(), sizes.data(),
                            static_cast<unsigned>(sizes.size()));
  if (ZDICT_isError(size)) {
    return InvalidArgumentError(std::string("zstd dictionary training on ") +
                                std::to_string(sizes.size()) +
                                " samples failed: " + ZDICT_getErrorName(size));
  }
  dictionary.resize(size);
  return ZstdDictionary(std::move(dictionary));
}

StatusOr<std::vector<uint8_t>> ZstdDictionary::Compress(std::span<const uint8_t> bytes,
                                                        int level) const {
  if (level < 1 || level > ZSTD_maxCLevel()) {
    return InvalidArgumentError("zstd level " + std::to_string(level) + " is not in 1.." +
                                std::to_string(ZSTD_maxCLevel()));
  }
  const std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(),
                                                                     &ZSTD_freeCCtx);
  if (context == nullptr) return InternalError("zstd: cannot create a compression context");
  const auto check = [](size_t result) -> Status {
    if (ZSTD_isError(result))
      return InternalError(std::string("zstd: ") + ZSTD_getErrorName(result));
    return Status::Ok();
  };
  FLEETMAP_RETURN_IF_ERROR(
      check(ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, level)));
  FLEETMAP_RETURN_IF_ERROR(check(ZSTD_CCtx_setParameter(context.get(), ZSTD_c_dictIDFlag, 0)));
  FLEETMAP_RETURN_IF_ERROR(
      check(ZSTD_CCtx_loadDictionary(context.get(), bytes_->data(), bytes_->size())));
  std::vector<uint8_t> out(ZSTD_compressBound(bytes.size()));
  const size_t size =
      ZSTD_compress2(context.get(), out.data(), out.size(), bytes.data(), bytes.size());
  FLEETMAP_RETURN_IF_ERROR(check(size));
  out.resize(size);
  return out;
}

StatusOr<std::vector<uint8_t>> ZstdDictionary::Decompress(std::span<const uint8_t> frame) const {
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN) {
    return InvalidArgumentError("zstd: not a frame with its content size");
  }
  const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(),
                                                                     &ZSTD_freeDCtx);
  if (context == nullptr) return InternalError("zstd: cannot create a decompression context");
  std::vector<uint8_t> out(static_cast<size_t>(content));
  const size_t size = ZSTD_decompress_usingDict(context.get(), out.data(), out.size(), frame.data(),
                                                frame.size(), bytes_->data(), bytes_->size());
  if (ZSTD_isError(size))
    return InvalidArgumentError(std::string("zstd: ") + ZSTD_getErrorName(size));
  out.resize(size);
  return out;
}

}  // namespace fleetmap::bench
