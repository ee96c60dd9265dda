#pragma once

// The page's JSON for what it draws: fused vector tiles, sub-maps and learned objects, in the fleet
// frame, metres rounded to millimetres (docs/view.md, "The event stream", gives every field). The
// page draws exactly this; nothing here knows about clients or deltas.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/core/ids.hpp"
#include "common/transport/state_messages.hpp"
#include "common/transport/vector_tile_message.hpp"

namespace fleetmap::view {

// [x0, y0, x1, y1, ...]: points in metres, rounded to millimetres.
nlohmann::json FlatPoints(const std::vector<Point2>& points);

// "x,y": a tile's key in the page's dictionaries.
std::string TileKey(const TileId& tile);

// {key, x, y, rev, size, res, ob: [[half_width, closed, x0, y0, x1, y1, ...], ...],
//  fr: [[[outer x0, y0, ...], [hole ...], ...], ...]}
nlohmann::json TileJson(const transport::VectorTileMessage& tile);

// {id, kind, state, precision, place, source, rings: [[x0, y0, ...], ...]}: the outline of the
// sub-map's navigable cells (free, or confidence above the prediction's threshold).
nlohmann::json SubmapJson(const transport::SubmapMessage& submap);

// {id, template, w, h, x, y, yaw, sightings}: where the object was last seen, and its extent.
nlohmann::json ObjectJson(const transport::ObjectModelMessage& object);

// {id, revision, frame, radius, nodes: [x0, y0, ...], kinds: ["doorway", ...], edges: [[start
// node index, end node index], ...], note}: the route graph (rt/fleetmap/route_graph), its nodes
// in the order of `kinds`.
nlohmann::json RouteGraphJson(const transport::RouteGraphMessage& graph);

// {id, objects, w, h}
nlohmann::json TemplateJson(const transport::ObjectTemplateMessage& object_template);

}  // namespace fleetmap::view
