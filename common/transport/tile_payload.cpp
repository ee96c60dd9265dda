#include "common/transport/tile_payload.hpp"

#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/idl_shapes.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"

namespace fleetmap::transport {

using fleetmap_msgs::msg::dds_::VectorTile_;

StatusOr<std::string> EncodeTilePayload(const VectorTileMessage& tile) {
  FLEETMAP_ASSIGN_OR_RETURN(const VectorTile_ sample, ToIdl(tile));
  return SerializeCdr(sample);
}

StatusOr<VectorTileMessage> DecodeTilePayload(std::string_view bytes, const std::string& name,
                                              const TileDecodeLimits& limits) {
  VectorTile_ sample;
  FLEETMAP_RETURN_IF_ERROR(
      DeserializeCdr(bytes, VectorTileShape(), name + ": not a vector tile", &sample));
  StatusOr<VectorTileMessage> tile = FromIdl(sample, limits);
  if (!tile.ok()) return tile.status().WithContext(name);
  return tile;
}

}  // namespace fleetmap::transport
