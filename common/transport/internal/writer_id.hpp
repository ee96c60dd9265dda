#pragma once

// Internal to transport: a printable id of the DDS writer that sent a sample, from its instance
// handle (the writer's GUID), so the nodes can tell two writers apart without Fast DDS types.

#include <fastdds/rtps/common/InstanceHandle.h>

#include <string>

namespace fleetmap::transport {

inline std::string WriterId(const eprosima::fastrtps::rtps::InstanceHandle_t& handle) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id;
  id.reserve(32);
  for (size_t i = 0; i < 16; ++i) {
    const auto byte = static_cast<uint8_t>(handle.value[i]);
    id.push_back(kHex[(byte >> 4) & 0xf]);
    id.push_back(kHex[byte & 0xf]);
  }
  return id;
}

}  // namespace fleetmap::transport
