#pragma once

// A robot contribution's evidence as bytes, for the map store's tile_evidence rows
// (docs/file-formats.md, "Map store"): a small header, then one zstd frame holding the cells and,
// byte plane by byte plane, their evidence dates. The store never decodes it.

#include <string>
#include <string_view>

#include "common/core/status.hpp"
#include "common/fusion/tile_fusion.hpp"

namespace fleetmap::fusion {

StatusOr<std::string> EncodeEvidence(const ContributionEvidence& evidence);
// Checks the header, that the tile has `cells_per_tile` cells per side and every length before
// and after decompressing; `name` prefixes errors. Cell values are checked by
// TileFusion::ImportContribution.
StatusOr<ContributionEvidence> DecodeEvidence(std::string_view bytes, int cells_per_tile,
                                              const std::string& name);

}  // namespace fleetmap::fusion
