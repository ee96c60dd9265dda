// Fuzz target: a map image as `fleetmap-agent --map` and every map command load it (PGM with
// fleetmap's own reader; PNG and BMP through the header check, then OpenCV). The bytes go to a
// file without an extension, so the loader picks the decoder by content, as it does for an image
// of any name. The limits are below the defaults so that a header's size costs the fuzzer little,
// and the grid that comes back has the size the limits allow.

#include <cstddef>
#include <cstdint>

#include "common/core/check.hpp"
#include "common/grid/map_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  static const std::string path = (fuzz::ScratchFolder() / "image").string();
  fuzz::WriteScratchFile(path, fuzz::AsText(data, size));
  grid::MapMetadata metadata;
  metadata.image = "image";
  metadata.image_path = path;
  // Both readings of the shades: trinary (alpha averaged in) and scale (alpha is unknown).
  metadata.mode = size % 2 == 0 ? grid::MapMode::kTrinary : grid::MapMode::kScale;
  grid::MapLoadOptions options;
  options.max_cells = 1 << 20;
  options.max_decoded_bytes = 16 << 20;
  const StatusOr<grid::OccupancyGrid> grid = grid::LoadMapImage(metadata, options);
  if (!grid.ok()) return 0;
  FLEETMAP_CHECK(grid->width() > 0 && grid->height() > 0);
  FLEETMAP_CHECK(int64_t{grid->width()} * grid->height() <= options.max_cells);
  for (const int8_t value : grid->data()) FLEETMAP_CHECK(value >= -1 && value <= 100);
  return 0;
}
