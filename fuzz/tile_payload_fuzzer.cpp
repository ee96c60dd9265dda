// Fuzz target: a vector tile payload, the bytes of one rt/fleetmap/robot_tiles (or fused_tiles)
// sample and of a tile in the server's store: the CDR shape check, fastcdr, then the layout-5
// codec (plain and zstd geometry). What decodes must encode again and decode to the same tile: the
// codec may refuse a tile, never misread one.

#include <cstddef>
#include <cstdint>

#include "common/core/check.hpp"
#include "common/transport/tile_payload.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const StatusOr<transport::VectorTileMessage> tile =
      transport::DecodeTilePayload(fuzz::AsText(data, size), "fuzz");
  if (!tile.ok()) return 0;
  const StatusOr<std::string> again = transport::EncodeTilePayload(*tile);
  FLEETMAP_CHECK(again.ok(), again.status().message());
  const StatusOr<transport::VectorTileMessage> back =
      transport::DecodeTilePayload(*again, "re-encoded");
  FLEETMAP_CHECK(back.ok(), back.status().message());
  FLEETMAP_CHECK(back->robot_id == tile->robot_id && back->tile == tile->tile &&
                 back->revision == tile->revision && back->tile_size == tile->tile_size);
  FLEETMAP_CHECK(back->map.obstacles == tile->map.obstacles, "obstacles changed on a round trip");
  FLEETMAP_CHECK(back->map.free_space == tile->map.free_space,
                 "free space changed on a round trip");
  return 0;
}
