#include "common/route_graph/route_graph_export.hpp"

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

#include "common/core/number_format.hpp"

namespace fleetmap::route_graph {
namespace {

constexpr int kDecimals = 4;

double Coordinate(double value) { return RoundToDecimals(value, kDecimals); }

nlohmann::json EdgeFeature(const RouteGraph& graph, const RouteEdge& edge, bool reverse) {
  const uint32_t start = reverse ? edge.end : edge.start;
  const uint32_t end = reverse ? edge.start : edge.end;
  const RouteNode* from = graph.FindNode(start);
  const RouteNode* to = graph.FindNode(end);
  nlohmann::json properties = {
      {"id", reverse ? edge.reverse_id : edge.id},
      {"startid", start},
      {"endid", end},
      {"cost", RoundToDecimals(edge.length, kDecimals)},
      {"overridable", true},
      {"metadata",
       {{"length", RoundToDecimals(edge.length, kDecimals)},
        {"clearance", RoundToDecimals(edge.clearance, kDecimals)},
        {"predicted", edge.predicted}}},
  };
  if (edge.blocking_object) {
    properties["metadata"]["blocked_by_object"] = *edge.blocking_object;
  }
  nlohmann::json line = nlohmann::json::array();
  line.push_back({Coordinate(from->position.x()), Coordinate(from->position.y())});
  line.push_back({Coordinate(to->position.x()), Coordinate(to->position.y())});
  return {
      {"type", "Feature"},
      {"properties", std::move(properties)},
      {"geometry", {{"type", "MultiLineString"}, {"coordinates", nlohmann::json::array({line})}}},
  };
}

}  // namespace

nlohmann::json Nav2RouteGeoJson(const RouteGraph& graph) {
  nlohmann::json features = nlohmann::json::array();
  for (const RouteNode& node : graph.nodes) {
    features.push_back({
        {"type", "Feature"},
        {"properties",
         {{"id", node.id},
          {"frame", graph.frame},
          {"metadata",
           {{"kind", std::string(RouteNodeKindName(node.kind))},
            {"clearance", RoundToDecimals(node.clearance, kDecimals)},
            {"predicted", node.predicted}}}}},
        {"geometry",
         {{"type", "Point"},
          {"coordinates", {Coordinate(node.position.x()), Coordinate(node.position.y())}}}},
    });
  }
  for (const RouteEdge& edge : graph.edges) {
    features.push_back(EdgeFeature(graph, edge, false));
    features.push_back(EdgeFeature(graph, edge, true));
  }
  return {{"type", "FeatureCollection"}, {"name", "fleetmap_route_graph"}, {"features", features}};
}

std::string RmfNavGraphYaml(const RouteGraph& graph, const std::string& level) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "building_name" << YAML::Value << "fleetmap";
  out << YAML::Key << "lifts" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::EndMap;
  out << YAML::Key << "levels" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << level << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "vertices" << YAML::Value << YAML::BeginSeq;
  for (const RouteNode& node : graph.nodes) {
    std::string name = "n";
    name.append(std::to_string(node.id));
    out << YAML::Flow << YAML::BeginSeq << FixedNumber(node.position.x(), kDecimals)
        << FixedNumber(node.position.y(), kDecimals) << YAML::BeginMap << YAML::Key << "name"
        << YAML::Value << name << YAML::EndMap << YAML::EndSeq;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "lanes" << YAML::Value << YAML::BeginSeq;
  for (const RouteEdge& edge : graph.edges) {
    const size_t start = *graph.NodeIndex(edge.start);
    const size_t end = *graph.NodeIndex(edge.end);
    for (const auto& [from, to] : {std::pair{start, end}, std::pair{end, start}}) {
      // rmf_fleet_adapter reads the properties it knows and passes over the others.
      out << YAML::Flow << YAML::BeginSeq << from << to << YAML::BeginMap;
      if (edge.predicted) out << YAML::Key << "fleetmap_predicted" << YAML::Value << true;
      if (edge.blocking_object) {
        out << YAML::Key << "fleetmap_blocked_by_object" << YAML::Value << *edge.blocking_object;
      }
      out << YAML::EndMap << YAML::EndSeq;
    }
  }
  out << YAML::EndSeq;
  out << YAML::EndMap << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace fleetmap::route_graph
