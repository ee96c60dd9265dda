// Fuzz target: a vector tile's geometry string (docs/file-formats.md, "VectorTile, field by
// field"), reached without the CDR around it so that every mutation lands in the varints. The
// first byte picks how the bytes travel: plain, zstd-compressed here (so the fuzzer's bytes are
// what the decompressed string holds), or as a zstd frame of the fuzzer's own making; the second
// picks the tile size and resolution, the next two the tile's key (signed). What decodes must
// encode and decode to the same map.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/check.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/internal/zstd_frame.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  if (size < 4) return 0;
  const uint8_t mode = data[0] % 3;
  const uint8_t sizes = data[1];
  const std::span<const uint8_t> geometry(data + 4, size - 4);

  constexpr std::array<uint32_t, 4> kTileSizesMm = {10000, 5000, 1000, 65535};
  constexpr std::array<float, 4> kResolutions = {0.05F, 0.1F, 0.025F, 0.001F};
  fleetmap_msgs::msg::dds_::VectorTile_ tile;
  tile.robot_id("alpha");
  tile.tile_x(static_cast<int8_t>(data[2]));
  tile.tile_y(static_cast<int8_t>(data[3]));
  tile.layout_version(5);
  tile.revision(1);
  tile.tile_size_mm(kTileSizesMm[sizes & 3]);
  tile.resolution(kResolutions[(sizes >> 2) & 3]);
  tile.epsilon(tile.resolution() * ((sizes & 0x10) != 0 ? 0.0F : 1.5F));
  if (mode == 0) {
    tile.compression(0);
    tile.geometry(std::vector<uint8_t>(geometry.begin(), geometry.end()));
  } else if (mode == 1) {
    tile.compression(1);
    tile.geometry(transport::ZstdCompress(geometry, 1));
  } else {
    tile.compression(1);
    tile.geometry(std::vector<uint8_t>(geometry.begin(), geometry.end()));
  }

  const StatusOr<transport::VectorTileMessage> decoded = transport::FromIdl(tile);
  if (!decoded.ok()) return 0;
  const auto again = transport::ToIdl(*decoded);
  FLEETMAP_CHECK(again.ok(), again.status().message());
  const StatusOr<transport::VectorTileMessage> back = transport::FromIdl(*again);
  FLEETMAP_CHECK(back.ok(), back.status().message());
  FLEETMAP_CHECK(back->map.obstacles == decoded->map.obstacles,
                 "obstacles changed on a round trip");
  FLEETMAP_CHECK(back->map.free_space == decoded->map.free_space,
                 "free space changed on a round trip");
  return 0;
}
