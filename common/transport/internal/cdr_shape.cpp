#include "common/transport/internal/cdr_shape.hpp"

#include <cstring>

namespace fleetmap::transport {
namespace {

// Bound on nesting, so a shape can never recurse without end.
constexpr int kMaxDepth = 8;

class CdrWalker {
 public:
  CdrWalker(std::span<const uint8_t> data, bool little_endian)
      : data_(data), little_endian_(little_endian) {}

  Status Walk(const CdrShape& shape, const std::string& path, int depth) {
    if (depth > kMaxDepth) return InternalError("CDR shape nests too deep at " + path);
    for (const CdrField& field : shape) {
      const std::string where = path.empty() ? field.name : path + "." + field.name;
      FLEETMAP_RETURN_IF_ERROR(WalkField(field, where, depth));
    }
    return Status::Ok();
  }

  size_t position() const { return position_; }

 private:
  Status WalkField(const CdrField& field, const std::string& where, int depth) {
    switch (field.kind) {
      case CdrField::Kind::kPrimitive:
        return Take(field.size, field.size, where);
      case CdrField::Kind::kString: {
        uint32_t length = 0;
        FLEETMAP_RETURN_IF_ERROR(ReadLength(&length, where));
        return Take(length, 1, where);
      }
      case CdrField::Kind::kPrimitiveSequence: {
        uint32_t count = 0;
        FLEETMAP_RETURN_IF_ERROR(ReadLength(&count, where));
        if (count == 0) return Status::Ok();
        if (count > (Remaining() + field.size) / field.size) return TooLong(where, count);
        return Take(static_cast<size_t>(count) * field.size, field.size, where);
      }
      case CdrField::Kind::kStruct:
        return Walk(*field.shape, where, depth + 1);
      case CdrField::Kind::kStructSequence: {
        uint32_t count = 0;
        FLEETMAP_RETURN_IF_ERROR(ReadLength(&count, where));
        // Every struct takes at least one byte, so a count beyond the bytes left is a lie.
        if (count > Remaining()) return TooLong(where, count);
        for (uint32_t i = 0; i < count; ++i) {
          FLEETMAP_RETURN_IF_ERROR(
              Walk(*field.shape, where + "[" + std::to_string(i) + "]", depth + 1));
        }
        return Status::Ok();
      }
    }
    return InternalError("unknown CDR field kind at " + where);
  }

  size_t Remaining() const { return data_.size() - position_; }

  Status Align(size_t alignment, const std::string& where) {
    if (alignment <= 1) return Status::Ok();
    const size_t padding = (alignment - position_ % alignment) % alignment;
    if (padding > Remaining()) return Truncated(where);
    position_ += padding;
    return Status::Ok();
  }

  Status Take(size_t bytes, size_t alignment, const std::string& where) {
    FLEETMAP_RETURN_IF_ERROR(Align(alignment, where));
    if (bytes > Remaining()) return Truncated(where);
    position_ += bytes;
    return Status::Ok();
  }

  Status ReadLength(uint32_t* value, const std::string& where) {
    FLEETMAP_RETURN_IF_ERROR(Align(4, where));
    if (Remaining() < 4) return Truncated(where);
    uint8_t bytes[4];
    std::memcpy(bytes, data_.data() + position_, 4);
    position_ += 4;
    *value = little_endian_ ? (uint32_t{bytes[0]} | uint32_t{bytes[1]} << 8 |
                               uint32_t{bytes[2]} << 16 | uint32_t{bytes[3]} << 24)
                            : (uint32_t{bytes[3]} | uint32_t{bytes[2]} << 8 |
                               uint32_t{bytes[1]} << 16 | uint32_t{bytes[0]} << 24);
    return Status::Ok();
  }

  Status Truncated(const std::string& where) const {
    return DataLossError("truncated at " + where + " (byte " + std::to_string(position_ + 4) +
                         " of " + std::to_string(data_.size() + 4) + ")");
  }

  Status TooLong(const std::string& where, uint32_t count) const {
    return DataLossError(where + " claims " + std::to_string(count) + " elements but only " +
                         std::to_string(Remaining()) + " bytes remain");
  }

  std::span<const uint8_t> data_;
  bool little_endian_;
  size_t position_ = 0;
};

}  // namespace

Status CheckCdr(std::span<const uint8_t> payload, const CdrShape& shape, size_t* consumed) {
  if (payload.size() < 4) {
    return DataLossError("too short for a CDR encapsulation header (" +
                         std::to_string(payload.size()) + " bytes)");
  }
  // Encapsulation: 0x00 0x00 = CDR big-endian, 0x00 0x01 = CDR little-endian (XCDR1, final).
  if (payload[0] != 0 || payload[1] > 1) {
    return DataLossError("not a plain CDR payload (encapsulation " + std::to_string(payload[0]) +
                         " " + std::to_string(payload[1]) + ")");
  }
  CdrWalker walker(payload.subspan(4), payload[1] == 1);
  FLEETMAP_RETURN_IF_ERROR(walker.Walk(shape, "", 0));
  if (consumed != nullptr) *consumed = walker.position();
  return Status::Ok();
}

}  // namespace fleetmap::transport
