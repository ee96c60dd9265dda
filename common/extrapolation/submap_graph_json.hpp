#pragma once

// The sub-map graph as JSON (the `extrapolate` output, docs/extrapolation.md): sub-maps with
// their kind, place, pose, elevation, entities, grid geometry and free-cell counts, edges with
// their relative transforms, and the places with their sub-maps. Grids themselves are written as
// map_server files beside it.

#include <string>

#include <nlohmann/json.hpp>

#include "common/scene/submap_graph.hpp"

namespace fleetmap::extrapolation {

// `grid_files[i]`, if given, names the map YAML written for sub-map i.
nlohmann::json SubmapGraphToJson(const scene::SubmapGraph& graph,
                                 const std::vector<std::string>& grid_files = {});

}  // namespace fleetmap::extrapolation
