#pragma once

// The route graph in the formats fleet managers load (docs/route-graph.md, "Exports"):
//  - nav2_route's GeoJSON graph file: a FeatureCollection whose nodes are Point features with
//    properties `id` and `frame`, and whose edges are MultiLineString features with `id`,
//    `startid`, `endid` and `cost`. nav2 edges are directed: each undirected edge is written twice
//    (`id` from start to end, `reverse_id` back); ids are unique across nodes and edges, as
//    nav2_route requires. `cost` is the edge's length in metres, `overridable` so that nav2's edge
//    scorers may weigh it; fleetmap's extras sit in `metadata` (kind, clearance, length,
//    `predicted`, and `blocked_by_object` with the object's id on an edge a movable object blocks).
//  - Open-RMF's nav graph YAML for one level, as rmf_fleet_adapter's parse_graph reads it:
//    `levels: {<level>: {vertices: [[x, y, {name}]], lanes: [[v0, v1, {}]]}}`, vertices indexed by
//    their place in the list, each lane one way (so two per edge), names `n<id>` (stable); a lane
//    through predicted space has `fleetmap_predicted: true`, one a learned object blocks
//    `fleetmap_blocked_by_object: <id>` (properties parse_graph passes over).
// Coordinates are map-frame metres rounded to 0.1 mm.

#include <string>

#include <nlohmann/json.hpp>

#include "common/route_graph/route_graph.hpp"

namespace fleetmap::route_graph {

nlohmann::json Nav2RouteGeoJson(const RouteGraph& graph);

// `level` is the level's name in the building (Open-RMF's traffic editor names them L1, L2...).
std::string RmfNavGraphYaml(const RouteGraph& graph, const std::string& level = "L1");

}  // namespace fleetmap::route_graph
