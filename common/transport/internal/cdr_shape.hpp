#pragma once

// Checks a plain-CDR (XCDR1) payload against the shape of its type before fastcdr decodes it.
// fastcdr trusts every sequence and string length it reads and allocates what the length says,
// so a corrupt .vmap file or a hostile DDS sample could make it allocate gigabytes. CheckCdr walks
// the payload once, with the same alignment rules, and refuses any length that does not fit in the
// bytes that remain. The shapes are written next to the .idl files' conversions (idl_shapes.cpp),
// and a round-trip test keeps them in step with the generated code.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::transport {

struct CdrField;
using CdrShape = std::vector<CdrField>;

struct CdrField {
  enum class Kind : uint8_t {
    kPrimitive,          // `size` bytes, aligned to `size`
    kString,             // uint32 length (with the terminating NUL), then the bytes
    kPrimitiveSequence,  // uint32 count, then count elements of `size` bytes
    kStruct,             // the fields of `shape`, in order
    kStructSequence,     // uint32 count, then count structs of `shape`
  };
  const char* name = "";
  Kind kind = Kind::kPrimitive;
  size_t size = 0;
  const CdrShape* shape = nullptr;
};

// `payload` is a whole DDS serialized payload: the 4-byte encapsulation header (CDR_BE or CDR_LE)
// then the data. The error names the field where the payload stops making sense.
// `consumed`, if given, receives the bytes the data took (after the header, before any padding).
Status CheckCdr(std::span<const uint8_t> payload, const CdrShape& shape,
                size_t* consumed = nullptr);

}  // namespace fleetmap::transport
