#pragma once

// The compressors of the grid baselines. Each call compresses its buffer alone (no state carried
// from one call to the next), as each tile travels alone on the wire; the dictionary baseline
// shares only a dictionary trained beforehand, as a fleet would ship one with its software.

#include <cstddef>
#include <cstdint>
#include <memory>
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

// A zstd dictionary, as `zstd --train` makes one (the same trainer, ZDICT_trainFromBuffer, and
// its default capacity of 110 KB), for the strongest grid baseline a careful engineer would build:
// every tile zstd -19 against a dictionary trained on the grid tiles of other maps, shipped once
// with the fleet's software and so not counted per tile. Immutable once trained; any thread.
class ZstdDictionary {
 public:
  static constexpr size_t kDefaultCapacity = 112640;  // zstd --train's --maxdict

  // Trains on `samples` (each one tile's cells). Errors: fewer than 8 non-empty samples, or what
  // the trainer says (e.g. samples too small or too alike to learn from).
  static StatusOr<ZstdDictionary> Train(const std::vector<std::vector<uint8_t>>& samples,
                                        size_t capacity = kDefaultCapacity);

  // One frame at `level` (1..19) against the dictionary. The frame names no dictionary id (the
  // fleet has one), which favours the baseline by up to 4 bytes; the content size is written, as
  // for CompressZstd.
  StatusOr<std::vector<uint8_t>> Compress(std::span<const uint8_t> bytes, int level) const;
  // Decompresses a frame Compress() made (for tests: the baseline must round-trip).
  StatusOr<std::vector<uint8_t>> Decompress(std::span<const uint8_t> frame) const;

  size_t size() const { return bytes_->size(); }

 private:
  explicit ZstdDictionary(std::vector<uint8_t> bytes)
      : bytes_(std::make_shared<const std::vector<uint8_t>>(std::move(bytes))) {}

  std::shared_ptr<const std::vector<uint8_t>> bytes_;
};

}  // namespace fleetmap::bench
