#pragma once

// What the vector-map subcommands share: reading their inputs and checking their numeric options.
// Every error message names the file (or flag) and the problem, ready for "fleetmap <cmd>: ...".

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/core/status.hpp"
#include "common/grid/map_io.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::cli {

// The default --max-cells of every subcommand that reads or makes a grid.
inline constexpr int64_t kDefaultMaxCells = 400'000'000;

// grid::LoadMap with a cell limit (kResourceExhausted past it).
StatusOr<grid::LoadedMap> LoadGridInput(const std::string& yaml_path, int64_t max_cells);

// transport::ReadVmapFile: missing, truncated or corrupt files are errors naming `path`.
StatusOr<vector_map::TiledVectorMap> ReadVmapInput(const std::string& path);

// `value` must be a finite number > 0 (NaN and infinities are refused): "<flag> must be ...".
Status CheckPositiveFinite(const std::string& flag, double value);

// A .vmap holds fleet-frame tiles of an axis-aligned grid with fleet_from_map = identity, so a
// grid whose origin is rotated cannot be tiled or compared with one.
Status CheckAxisAligned(const std::string& yaml_path, const grid::OccupancyGrid& grid);

// An unknown-filled grid covering every tile square of `map` at `resolution` (the default
// geometry of `rasterize` and `render`). Errors: no tiles, a bad resolution, or more than
// `max_cells` cells (a corrupt tile index must not allocate the world).
StatusOr<grid::OccupancyGrid> TileBoundsGrid(const vector_map::TiledVectorMap& map,
                                             const std::string& vmap_path, double resolution,
                                             int64_t max_cells);

// A .vmap stores resolution and epsilon as float32. The shortest decimal that reads back as the
// same float: 0.05f gives 0.05, not 0.05000000074505806.
double ShortestDouble(float value);

// The .vmap bytes of `map`. The vectorizer can emit free rings of one or two vertices (free specks
// one or two cells across); they are kept when the codec takes them. A codec that refuses rings
// without area gets them left out of `map` (an outer ring takes its holes with it) and encodes
// again; `*dropped_free_rings` says how many were left out.
StatusOr<std::string> EncodeVmapBytes(vector_map::TiledVectorMap* map, size_t* dropped_free_rings);

// The epsilon to validate a .vmap with: its float32 epsilon was rounded to nearest from the one
// the geometry was built with, so one float step up is a sound bound (a few nanometres more).
double StoredEpsilonBound(double stored_epsilon);

// Whether `path` ends with `extension` (".png"), ignoring ASCII case.
bool HasExtension(const std::string& path, const std::string& extension);

}  // namespace fleetmap::cli
