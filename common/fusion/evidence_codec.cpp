#include "common/fusion/evidence_codec.hpp"

#include <zstd.h>

#include <cstring>

namespace fleetmap::fusion {
namespace {

// Header: magic, format version, cells per side (uint32), stamp (int64 ns since the Unix epoch),
// little endian; then the zstd frame.
constexpr char kMagic[4] = {'F', 'M', 'E', 'V'};
constexpr uint8_t kVersion = 1;
constexpr size_t kHeaderSize = 4 + 1 + 4 + 8;
// Small tiles, written on the fusion thread: a fast level. The dates compress to a few bytes per
// run of equal values.
constexpr int kZstdLevel = 3;

void PutLittleEndian(uint64_t value, int bytes, std::string* out) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

uint64_t GetLittleEndian(std::string_view bytes, size_t at, int count) {
  uint64_t value = 0;
  for (int i = 0; i < count; ++i) {
    value |= static_cast<uint64_t>(static_cast<uint8_t>(bytes[at + static_cast<size_t>(i)]))
             << (8 * i);
  }
  return value;
}

}  // namespace

StatusOr<std::string> EncodeEvidence(const ContributionEvidence& evidence) {
  const size_t count = evidence.cells.size();
  if (evidence.changed_at.size() != count) {
    return InvalidArgumentError("evidence: " + std::to_string(count) + " cells but " +
                                std::to_string(evidence.changed_at.size()) + " dates");
  }
  size_t side = 0;
  while (side * side < count) ++side;
  if (side * side != count) {
    return InvalidArgumentError("evidence: " + std::to_string(count) + " cells is not a square");
  }
  // Cells, then each byte of the dates as its own plane: equal dates make long equal runs.
  std::string raw(count * 5, '\0');
  std::memcpy(raw.data(), evidence.cells.data(), count);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t at = evidence.changed_at[i];
    for (size_t b = 0; b < 4; ++b) {
      raw[count * (1 + b) + i] = static_cast<char>((at >> (8 * b)) & 0xff);
    }
  }
  std::string out(kMagic, sizeof(kMagic));
  out.push_back(static_cast<char>(kVersion));
  PutLittleEndian(side, 4, &out);
  const int64_t stamp_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(evidence.stamp.time_since_epoch())
          .count();
  PutLittleEndian(static_cast<uint64_t>(stamp_ns), 8, &out);
  out.resize(kHeaderSize + ZSTD_compressBound(raw.size()));
  const size_t size = ZSTD_compress(out.data() + kHeaderSize, out.size() - kHeaderSize, raw.data(),
                                    raw.size(), kZstdLevel);
  if (ZSTD_isError(size))
    return InternalError(std::string("evidence: zstd: ") + ZSTD_getErrorName(size));
  out.resize(kHeaderSize + size);
  return out;
}

StatusOr<ContributionEvidence> DecodeEvidence(std::string_view bytes, int cells_per_tile,
                                              const std::string& name) {
  if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    return DataLossError(name + ": not fleetmap tile evidence (" + std::to_string(bytes.size()) +
                         " bytes, no FMEV header)");
  }
  if (static_cast<uint8_t>(bytes[4]) != kVersion) {
    return DataLossError(name + ": tile evidence format " +
                         std::to_string(static_cast<uint8_t>(bytes[4])) + " is not " +
                         std::to_string(kVersion));
  }
  const uint64_t side = GetLittleEndian(bytes, 5, 4);
  if (side != static_cast<uint64_t>(cells_per_tile)) {
    return InvalidArgumentError(name + ": tile evidence has " + std::to_string(side) +
                                " cells per side, the fusion " + std::to_string(cells_per_tile) +
                                " (tile size or resolution changed since it was stored)");
  }
  const auto stamp_ns = static_cast<int64_t>(GetLittleEndian(bytes, 9, 8));
  const size_t count = static_cast<size_t>(side * side);
  const std::string_view frame = bytes.substr(kHeaderSize);
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content != count * 5) {
    return DataLossError(name + ": tile evidence frame holds " +
                         (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN
                              ? std::string("no readable size")
                              : std::to_string(content) + " bytes") +
                         ", expected " + std::to_string(count * 5));
  }
  std::string raw(count * 5, '\0');
  const size_t size = ZSTD_decompress(raw.data(), raw.size(), frame.data(), frame.size());
  if (ZSTD_isError(size) || size != raw.size()) {
    return DataLossError(name + ": tile evidence does not decompress: " +
                         (ZSTD_isError(size) ? ZSTD_getErrorName(size) : "short frame"));
  }
  ContributionEvidence evidence;
  evidence.cells.resize(count);
  std::memcpy(evidence.cells.data(), raw.data(), count);
  evidence.changed_at.resize(count);
  for (size_t i = 0; i < count; ++i) {
    uint32_t at = 0;
    for (size_t b = 0; b < 4; ++b) {
      at |= static_cast<uint32_t>(static_cast<uint8_t>(raw[count * (1 + b) + i])) << (8 * b);
    }
    evidence.changed_at[i] = at;
  }
  evidence.stamp =
      Timestamp(std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(stamp_ns)));
  return evidence;
}

}  // namespace fleetmap::fusion
