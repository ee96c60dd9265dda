#pragma once

// The byte strings of the tile layout (docs/file-formats.md, "The geometry bytes"): unsigned
// LEB128 varints (7 bits per byte, low bits first, the high bit set on every byte but the last),
// zigzag for signed values (0, -1, 1, -2, ... as 0, 1, 2, 3, ...), plain bytes, and doubles as
// their eight IEEE 754 bytes, little-endian. Varint values are 64-bit.
//
// The reader never trusts the bytes: a varint with bits beyond 64, or a
// read past the end is an error naming the offset, never a crash.

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::transport {

class VarintWriter {
 public:
  void Unsigned(uint64_t value) {
    while (value >= 0x80) {
      bytes_.push_back(static_cast<uint8_t>(value | 0x80));
      value >>= 7;
    }
    bytes_.push_back(static_cast<uint8_t>(value));
  }
  void Signed(int64_t value) {
    Unsigned((static_cast<uint64_t>(value) << 1) ^ static_cast<uint64_t>(value >> 63));
  }
  void Byte(uint8_t value) { bytes_.push_back(value); }
  // Eight bytes, the IEEE 754 binary64 value little-endian.
  void Double(double value) {
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<uint8_t>(bits >> (8 * i)));
  }

  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

class VarintReader {
 public:
  explicit VarintReader(std::string_view bytes) : bytes_(bytes) {}

  StatusOr<uint64_t> Unsigned(const char* what) {
    uint64_t value = 0;
    for (int shift = 0; shift < 70; shift += 7) {
      if (offset_ >= bytes_.size()) return Truncated(what);
      const auto byte = static_cast<uint8_t>(bytes_[offset_++]);
      // The tenth byte holds bit 63 only: anything above it does not fit 64 bits.
      if (shift == 63 && byte > 0x01) break;
      value |= static_cast<uint64_t>(byte & 0x7F) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    return InvalidArgumentError(std::string(what) + " at byte " + std::to_string(offset_ - 1) +
                                " is a varint of more than 64 bits");
  }
  StatusOr<int64_t> Signed(const char* what) {
    FLEETMAP_ASSIGN_OR_RETURN(const uint64_t zigzag, Unsigned(what));
    return static_cast<int64_t>((zigzag >> 1) ^ (~(zigzag & 1) + 1));
  }
  StatusOr<uint8_t> Byte(const char* what) {
    if (offset_ >= bytes_.size()) return Truncated(what);
    return static_cast<uint8_t>(bytes_[offset_++]);
  }

  StatusOr<double> Double(const char* what) {
    if (remaining() < 8) return Truncated(what);
    uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) {
      bits |= static_cast<uint64_t>(static_cast<uint8_t>(bytes_[offset_++])) << (8 * i);
    }
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

  size_t remaining() const { return bytes_.size() - offset_; }
  size_t offset() const { return offset_; }

 private:
  Status Truncated(const char* what) const {
    return InvalidArgumentError(std::string(what) + " is cut off: the geometry ends at byte " +
                                std::to_string(bytes_.size()));
  }

  std::string_view bytes_;
  size_t offset_ = 0;
};

}  // namespace fleetmap::transport
