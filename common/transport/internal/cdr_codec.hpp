#pragma once

// Internal to transport: a generated type to and from the bytes of a DDS payload (encapsulation
// header + plain CDR), with the payload's lengths checked against the type's shape before fastcdr
// reads them (see cdr_shape.hpp).

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include <span>
#include <string>
#include <string_view>

#include "common/core/status.hpp"
#include "common/transport/internal/cdr_shape.hpp"

namespace fleetmap::transport {

// The bytes `sample` takes in a DDS payload: the 4-byte encapsulation header and its CDR. What
// every writer reports as published, so that all wires are counted alike.
template <typename Generated>
size_t PayloadBytes(const Generated& sample) {
  return Generated::getCdrSerializedSize(sample) + 4;
}

// Little-endian CDR, as most DDS implementations write it on x86 and ARM.
template <typename Generated>
std::string SerializeCdr(const Generated& sample) {
  std::string bytes(Generated::getCdrSerializedSize(sample) + 4, '\0');
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  sample.serialize(cdr);
  bytes.resize(cdr.getSerializedDataLength());
  return bytes;
}

// `what` names the expected content in errors ("not a valid .vmap").
template <typename Generated>
Status DeserializeCdr(std::string_view bytes, const CdrShape& shape, const std::string& what,
                      Generated* sample) {
  const std::span<const uint8_t> payload(reinterpret_cast<const uint8_t*>(bytes.data()),
                                         bytes.size());
  if (Status checked = CheckCdr(payload, shape); !checked.ok()) {
    return checked.WithContext(what);
  }
  try {
    std::string copy(bytes);  // fastcdr wants a mutable buffer; it only reads here
    eprosima::fastcdr::FastBuffer buffer(copy.data(), copy.size());
    eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                               eprosima::fastcdr::Cdr::DDS_CDR);
    cdr.read_encapsulation();
    sample->deserialize(cdr);
  } catch (const eprosima::fastcdr::exception::Exception& error) {
    return DataLossError(what + ": " + error.what());
  }
  return Status::Ok();
}

}  // namespace fleetmap::transport
