#pragma once

// How the drivers print a TileBytesComparison, so every report names the baselines the same way:
// a Markdown table (one row per map or terrain, a sum row, a ratio column per baseline and one
// against the smallest, each naming its baseline), the headline line under it, and CSV columns.

#include <ostream>
#include <string>
#include <vector>

#include "bench/bytes/tile_bytes_comparison.hpp"

namespace fleetmap::bench {

// `item` names what a row is ("map", "terrain"), in the first header and the headline. Needs at
// least one row (HeadlineOf).
void PrintTileBytesTable(const std::vector<NamedComparison>& rows, const std::string& item,
                         std::ostream& out);

// "vector tiles / smallest baseline: 0.62 summed (vs zstd -19); worst <item> 0.85 (<name>, vs
// zstd -19)".
std::string HeadlineText(const TileBytesHeadline& headline, const std::string& item);

// CSV columns of one comparison, in the same order as TileBytesCsvFields.
std::string TileBytesCsvHeader();
std::vector<std::string> TileBytesCsvFields(const TileBytesComparison& comparison);

}  // namespace fleetmap::bench
