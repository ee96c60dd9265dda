#pragma once

// What `fleetmap extrapolate` writes for one threshold (docs/extrapolation.md, "Outputs"): the
// predicted free space as GeoJSON (cv::findContours on each sub-map's free cells, vertices at cell
// centres, map frame, valid simple features with a `crs` member: docs/file-formats.md) and a PNG
// overlay of the local map with the predictions.

#include <string>

#include <nlohmann/json.hpp>

#include "common/core/status.hpp"
#include "common/extrapolation/extrapolator.hpp"
#include "common/extrapolation/predicted_free_grid.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::cli {

// Features for each connected free region of each predicted sub-map and of the people's
// conditionally free space (per observed sub-map, i.e. per place): its area as a (Multi)Polygon,
// and parts one cell wide as (Multi)LineString or (Multi)Point features, with the sub-map id, kind,
// class (static, quasi-static, dynamic), entities, elevation and p_th as properties. Errors
// (kInternal) only if GEOS fails on a region.
StatusOr<nlohmann::json> PredictedFreeGeoJson(const extrapolation::ExtrapolationResult& result,
                                              double p_th);

// Local map (occupied black, free white, unknown grey), predicted free space behind doors (green),
// people's conditionally free space (orange), the tracks (blue), the doors (purple, hinge dot) and
// the stairs' predicted landing on the floor above (red outline). Upright (north up).
Status WriteOverlayPng(const extrapolation::ExtrapolationResult& result,
                       const extrapolation::FloorGrids& floor, const scene::Entities& entities,
                       const std::string& path);

}  // namespace fleetmap::cli
