#pragma once

// .vmap files: exactly the CDR bytes of one fleetmap_msgs/msg/VectorMap (idl/), encapsulation
// header included, as a DDS payload. File format = wire format, so any CDR reader with the .idl
// files can open one. docs/file-formats.md describes the layout.

#include <cstddef>
#include <string>
#include <string_view>

#include "common/core/status.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::transport {

// Version 5 (tiles of layout 5: varint steps of a lattice tied to the resolution) replaced
// version 4 (uint8 obstacle sizes and half widths in steps of epsilon / 254) replaced version 3
// (uint16 for both, half widths in quanta), which replaced version 2 (quantum tile_size / 16384
// instead of tile_size / 16000), which replaced version 1 (uint32 counts, no point arrays, closed
// flags); a file of another version is refused with a message naming both.
inline constexpr char kVmapFormatPrefix[] = "fleetmap-vmap/";
inline constexpr char kVmapFormat[] = "fleetmap-vmap/5";

struct VmapReadOptions {
  size_t max_bytes = size_t{1} << 30;  // a larger file is refused before it is read
};

StatusOr<std::string> EncodeVmap(const vector_map::TiledVectorMap& map);
// `name` (a file name) prefixes every error. Never trusts a length it has not checked.
StatusOr<vector_map::TiledVectorMap> DecodeVmap(std::string_view bytes, const std::string& name);

// Writes EncodeVmap(map) to `path`, whole or not at all (WriteFileAtomically).
Status WriteVmapFile(const vector_map::TiledVectorMap& map, const std::string& path);
StatusOr<vector_map::TiledVectorMap> ReadVmapFile(const std::string& path,
                                                  const VmapReadOptions& options = {});

}  // namespace fleetmap::transport
