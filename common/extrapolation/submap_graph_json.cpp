#include "common/extrapolation/submap_graph_json.hpp"

#include <map>

namespace fleetmap::extrapolation {
namespace {

nlohmann::json PoseJson(const Pose2& pose) {
  return {{"x", pose.x}, {"y", pose.y}, {"yaw", pose.yaw}};
}

}  // namespace

nlohmann::json SubmapGraphToJson(const scene::SubmapGraph& graph,
                                 const std::vector<std::string>& grid_files) {
  nlohmann::json submaps = nlohmann::json::array();
  for (size_t i = 0; i < graph.submaps.size(); ++i) {
    const scene::Submap& s = graph.submaps[i];
    const grid::StateCounts counts = s.navigable.CountStates();
    nlohmann::json j = {
        {"id", s.id},
        {"kind", scene::SubmapKindName(s.kind)},
        {"place", s.place},
        {"map_from_submap", PoseJson(s.map_from_submap)},
        {"elevation", s.elevation},
        {"entities", s.entity_ids},
        {"grid",
         {{"width", s.navigable.width()},
          {"height", s.navigable.height()},
          {"resolution", s.navigable.resolution()},
          {"origin_in_submap", PoseJson(s.navigable.origin())},
          {"free_cells", counts.free},
          {"occupied_cells", counts.occupied},
          {"free_area_m2", static_cast<double>(counts.free) * s.navigable.resolution() *
                               s.navigable.resolution()}}},
    };
    if (i < grid_files.size() && !grid_files[i].empty()) j["grid"]["file"] = grid_files[i];
    submaps.push_back(std::move(j));
  }
  nlohmann::json edges = nlohmann::json::array();
  for (const scene::SubmapEdge& e : graph.edges) {
    edges.push_back({{"from", e.from},
                     {"to", e.to},
                     {"from_T_to", PoseJson(e.from_T_to)},
                     {"entity", e.entity_id}});
  }
  // Places: the sub-maps in each (an observed place holds one observed sub-map today, a
  // predicted place one predicted sub-map), in the order of their first sub-map.
  nlohmann::json places = nlohmann::json::array();
  std::map<uint32_t, size_t> place_index;
  for (const scene::Submap& s : graph.submaps) {
    const auto [it, inserted] = place_index.try_emplace(s.place, places.size());
    if (inserted) {
      places.push_back({{"place", s.place},
                        {"observed", s.kind == scene::SubmapKind::kObserved},
                        {"submaps", nlohmann::json::array()}});
    }
    places[it->second]["submaps"].push_back(s.id);
  }
  return {{"submaps", submaps}, {"edges", edges}, {"places", places}};
}

}  // namespace fleetmap::extrapolation
