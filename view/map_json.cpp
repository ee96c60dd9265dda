#include "view/map_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>

#include "common/grid/cell_rect.hpp"
#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/free_space_extractor.hpp"

namespace fleetmap::view {
namespace {

using nlohmann::json;

// Millimetres are far below what a page can show and keep the stream small.
double Millimetres(double metres) { return std::round(metres * 1000.0) / 1000.0; }

void AppendPoint(json& flat, const Point2& point) {
  flat.push_back(Millimetres(point.x()));
  flat.push_back(Millimetres(point.y()));
}

// The navigable cells of a sub-map as rings in the fleet frame, one cell's simplification error.
json NavigableRings(const transport::SubmapMessage& node) {
  const grid::OccupancyGrid& cells = node.submap.navigable;
  json rings = json::array();
  if (cells.empty()) return rings;
  const vector_map::CellFrame frame(cells);
  const Transform2 fleet_from_submap = node.submap.map_from_submap.ToTransform();
  const auto to_fleet = [&](const std::vector<Point2>& ring) {
    std::vector<Point2> fleet;
    fleet.reserve(ring.size());
    for (const Point2& point : ring) fleet.push_back(fleet_from_submap * frame.ToMap(point));
    return FlatPoints(fleet);
  };
  const grid::CellRect whole{0, 0, cells.width(), cells.height()};
  for (const vector_map::CellPolygon& polygon :
       vector_map::ExtractFreeSpace(cells, whole, {}, vector_map::FreeSpaceOptions{})) {
    rings.push_back(to_fleet(polygon.outer));
  }
  return rings;
}

json PatchExtent(const scene::Patch& patch) {
  return {{"w", Millimetres(patch.width * patch.resolution)},
          {"h", Millimetres(patch.height * patch.resolution)}};
}

}  // namespace

json FlatPoints(const std::vector<Point2>& points) {
  json flat = json::array();
  for (const Point2& point : points) AppendPoint(flat, point);
  return flat;
}

std::string TileKey(const TileId& tile) { return fmt::format("{},{}", tile.x, tile.y); }

json TileJson(const transport::VectorTileMessage& tile) {
  json obstacles = json::array();
  for (const vector_map::Polyline& line : tile.map.obstacles) {
    json flat = json::array({Millimetres(line.half_width), line.closed ? 1 : 0});
    for (const Point2& point : line.points) AppendPoint(flat, point);
    obstacles.push_back(std::move(flat));
  }
  json free_space = json::array();
  for (const vector_map::FreePolygon& polygon : tile.map.free_space) {
    json rings = json::array({FlatPoints(polygon.outer)});
    for (const auto& hole : polygon.holes) rings.push_back(FlatPoints(hole));
    free_space.push_back(std::move(rings));
  }
  return {{"key", TileKey(tile.tile)},
          {"x", tile.tile.x},
          {"y", tile.tile.y},
          {"rev", tile.revision},
          {"size", Millimetres(tile.tile_size)},
          // The free outlines pass through the centres of the boundary cells: the page widens
          // them by half a cell, as the rasterizer does, so neighbouring tiles meet. The wire's
          // float, rounded to micrometres, not its binary noise.
          {"res", std::round(tile.map.resolution * 1e6) / 1e6},
          {"ob", std::move(obstacles)},
          {"fr", std::move(free_space)}};
}

json SubmapJson(const transport::SubmapMessage& node) {
  const Pose2& pose = node.submap.map_from_submap;
  return {{"id", node.submap.id},
          {"kind", std::string(scene::SubmapKindName(node.submap.kind))},
          {"state", scene::SubmapStateName(node.state)},
          {"precision", node.precision < 0.0F ? json(nullptr) : json(Millimetres(node.precision))},
          {"place", node.submap.place},
          {"source", node.source_robot.value},
          {"x", Millimetres(pose.x)},
          {"y", Millimetres(pose.y)},
          {"rings", NavigableRings(node)}};
}

json RouteGraphJson(const transport::RouteGraphMessage& message) {
  const route_graph::RouteGraph& graph = message.graph;
  json nodes = json::array();
  json kinds = json::array();
  std::map<uint32_t, size_t> index;
  for (const route_graph::RouteNode& node : graph.nodes) {
    index[node.id] = kinds.size();
    AppendPoint(nodes, node.position);
    kinds.push_back(std::string(route_graph::RouteNodeKindName(node.kind)));
  }
  json edges = json::array();
  json predicted = json::array();  // indices into `edges`
  json blocked = json::array();    // [index into `edges`, object id]
  for (const route_graph::RouteEdge& edge : graph.edges) {
    const auto start = index.find(edge.start);
    const auto end = index.find(edge.end);
    if (start == index.end() || end == index.end()) continue;  // the reader checked; never here
    if (edge.predicted) predicted.push_back(edges.size());
    if (edge.blocking_object) blocked.push_back({edges.size(), *edge.blocking_object});
    edges.push_back({start->second, end->second});
  }
  return {{"id", message.graph_id},        {"revision", message.revision},
          {"frame", graph.frame},          {"radius", Millimetres(graph.robot_radius)},
          {"nodes", std::move(nodes)},     {"kinds", std::move(kinds)},
          {"edges", std::move(edges)},     {"predicted", std::move(predicted)},
          {"blocked", std::move(blocked)}, {"note", graph.message}};
}

json ObjectJson(const transport::ObjectModelMessage& object) {
  json sightings = json::array();
  for (const transport::ObjectSighting& sighting : object.sightings) {
    const Pose2& pose = sighting.fleet_from_object;
    sightings.push_back(
        {sighting.session, Millimetres(pose.x), Millimetres(pose.y), Millimetres(pose.yaw)});
  }
  json out = PatchExtent(object.patch);
  out["id"] = object.object_id;
  out["template"] = object.template_id;
  out["sightings"] = std::move(sightings);
  if (!object.sightings.empty()) {
    const Pose2& last = object.sightings.back().fleet_from_object;
    out["x"] = Millimetres(last.x);
    out["y"] = Millimetres(last.y);
    out["yaw"] = Millimetres(last.yaw);
  }
  return out;
}

json TemplateJson(const transport::ObjectTemplateMessage& object_template) {
  json out = PatchExtent(object_template.patch);
  out["id"] = object_template.template_id;
  out["objects"] = object_template.object_count;
  return out;
}

}  // namespace fleetmap::view
