#include "common/transport/vmap_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/core/file_io.hpp"
#include "common/core/number_format.hpp"
#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/idl_shapes.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "fleetmap_msgs/msg/VectorMap.h"

namespace fleetmap::transport {
namespace {

using fleetmap_msgs::msg::dds_::VectorMap_;

std::string TileName(const TileId& id) {
  return "tile (" + std::to_string(id.x) + ", " + std::to_string(id.y) + ")";
}

// The leading format string of a VectorMap, decoded on its own.
struct VmapFormatOnly {
  std::string format;
  void deserialize(eprosima::fastcdr::Cdr& cdr) { cdr >> format; }
};

// The format string is read from the first bytes only (decoding copies what it reads); a longer
// one is no version's.
constexpr size_t kFormatBytes = 4 + 4 + 1024;

// Every version starts with its format string: check it before the layout, so that a file of
// another version says so instead of failing somewhere in its tiles.
Status CheckFormat(std::string_view bytes, const std::string& name) {
  VmapFormatOnly header;
  const Status read = DeserializeCdr(bytes.substr(0, kFormatBytes), VmapFormatShape(),
                                     name + ": not a valid .vmap", &header);
  if (!read.ok() && bytes.size() > kFormatBytes) {
    return DataLossError(name + ": not a valid .vmap: no format string in its first " +
                         std::to_string(kFormatBytes) + " bytes");
  }
  FLEETMAP_RETURN_IF_ERROR(read);
  if (header.format == kVmapFormat) return Status::Ok();
  const std::string format = header.format.substr(0, 40);
  if (format.starts_with(kVmapFormatPrefix)) {
    return InvalidArgumentError(name + ": format " + format +
                                " is another version of the .vmap format; this fleetmap reads " +
                                kVmapFormat + " only (vectorize the map again to convert it)");
  }
  return InvalidArgumentError(name + ": format \"" + format + "\" is not " + kVmapFormat);
}

}  // namespace

StatusOr<std::string> EncodeVmap(const vector_map::TiledVectorMap& map) {
  VectorMap_ message;
  message.format(kVmapFormat);
  message.frame_id(map.frame_id);
  message.tile_size(map.tile_size);
  message.epsilon(static_cast<float>(map.epsilon));
  message.resolution(static_cast<float>(map.resolution));
  for (const auto& [id, tile] : map.tiles) {
    VectorTileMessage tile_message;
    tile_message.tile = id;
    tile_message.tile_size = map.tile_size;
    tile_message.map = tile;
    StatusOr<fleetmap_msgs::msg::dds_::VectorTile_> encoded = ToIdl(tile_message);
    if (!encoded.ok()) return encoded.status().WithContext(TileName(id));
    message.tiles().push_back(std::move(encoded).value());
  }
  return SerializeCdr(message);
}

StatusOr<vector_map::TiledVectorMap> DecodeVmap(std::string_view bytes, const std::string& name) {
  FLEETMAP_RETURN_IF_ERROR(CheckFormat(bytes, name));
  VectorMap_ message;
  FLEETMAP_RETURN_IF_ERROR(
      DeserializeCdr(bytes, VectorMapShape(), name + ": not a valid .vmap", &message));
  vector_map::TiledVectorMap map;
  map.frame_id = message.frame_id();
  map.tile_size = message.tile_size();
  // float32 in the file; the decimals the map was made with (0.05, not 0.05000000074505806).
  map.epsilon = DoubleFromFloat(message.epsilon());
  map.resolution = DoubleFromFloat(message.resolution());
  if (!std::isfinite(map.tile_size) || map.tile_size <= 0.0 || !std::isfinite(map.epsilon) ||
      map.epsilon < 0.0 || !std::isfinite(map.resolution) || map.resolution <= 0.0) {
    return InvalidArgumentError(name +
                                ": tile_size, epsilon or resolution is not a valid distance");
  }
  for (const auto& tile : message.tiles()) {
    const TileId id{tile.tile_x(), tile.tile_y()};
    StatusOr<VectorTileMessage> decoded = FromIdl(tile);
    if (!decoded.ok()) return decoded.status().WithContext(name + ": " + TileName(id));
    if (decoded->tile_size != map.tile_size) {
      return InvalidArgumentError(name + ": " + TileName(id) + " has tile_size " +
                                  std::to_string(decoded->tile_size) + ", the map " +
                                  std::to_string(map.tile_size));
    }
    if (map.tiles.empty()) map.lattice = decoded->map.lattice;
    if (!map.tiles.emplace(id, std::move(decoded->map)).second) {
      return InvalidArgumentError(name + ": " + TileName(id) + " appears twice");
    }
  }
  return map;
}

Status WriteVmapFile(const vector_map::TiledVectorMap& map, const std::string& path) {
  FLEETMAP_ASSIGN_OR_RETURN(const std::string bytes, EncodeVmap(map));
  return WriteFileAtomically(path, bytes);
}

StatusOr<vector_map::TiledVectorMap> ReadVmapFile(const std::string& path,
                                                  const VmapReadOptions& options) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return NotFoundError(path + ": no such file");
  }
  const auto size = std::filesystem::file_size(path, error);
  if (error) return NotFoundError(path + ": " + error.message());
  if (size > options.max_bytes) {
    return ResourceExhaustedError(path + ": " + std::to_string(size) + " bytes is over the " +
                                  std::to_string(options.max_bytes) + "-byte limit");
  }
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (!in) return DataLossError(path + ": read failed");
  return DecodeVmap(bytes, path);
}

}  // namespace fleetmap::transport
