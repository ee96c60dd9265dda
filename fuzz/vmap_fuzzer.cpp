// Fuzz target: a .vmap file (`fleetmap info|rasterize|compare ... x.vmap`, the server's exports):
// the format string, the CDR shape check, fastcdr, then every tile's layout-5 codec. A map that
// decodes must encode and decode again to the same tiles.

#include <cstddef>
#include <cstdint>

#include "common/core/check.hpp"
#include "common/transport/vmap_file.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const StatusOr<vector_map::TiledVectorMap> map =
      transport::DecodeVmap(fuzz::AsText(data, size), "fuzz.vmap");
  if (!map.ok()) return 0;
  const StatusOr<std::string> again = transport::EncodeVmap(*map);
  FLEETMAP_CHECK(again.ok(), again.status().message());
  const StatusOr<vector_map::TiledVectorMap> back = transport::DecodeVmap(*again, "re-encoded");
  FLEETMAP_CHECK(back.ok(), back.status().message());
  FLEETMAP_CHECK(back->tiles.size() == map->tiles.size());
  for (const auto& [id, tile] : map->tiles) {
    const auto found = back->tiles.find(id);
    FLEETMAP_CHECK(found != back->tiles.end(), "a tile was lost on a round trip");
    FLEETMAP_CHECK(
        found->second.obstacles == tile.obstacles && found->second.free_space == tile.free_space,
        "a tile changed on a round trip");
  }
  return 0;
}
