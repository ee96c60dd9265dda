#include "common/route_graph/route_graph_export.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "common/route_graph/route_graph_builder.hpp"
#include "tests/unit/route_graph/route_graph_test_maps.hpp"

namespace fleetmap::route_graph {
namespace {

using nlohmann::json;

// nav2_route's graph as its GeoJSON loader reads it: nodes by id, directed edges by id.
struct Nav2Graph {
  std::map<uint32_t, Point2> nodes;
  std::map<uint32_t, std::string> frames;
  struct Edge {
    uint32_t start = 0;
    uint32_t end = 0;
    double cost = -1.0;
  };
  std::map<uint32_t, Edge> edges;
};

// A strict reader of nav2_route's GeoJSON graph schema: everything the loader reads must be there
// with its type (ids unsigned integers, unique across nodes and edges; edges' ends existing
// nodes), and whatever is there must be what GeoJSON and the loader allow. Fails the test, saying
// what, on anything else.
Nav2Graph ReadNav2GraphStrictly(const json& document) {
  Nav2Graph graph;
  EXPECT_EQ(document.at("type"), "FeatureCollection");
  for (const auto& [key, value] : document.items()) {
    EXPECT_TRUE(key == "type" || key == "name" || key == "features") << "unexpected key " << key;
    (void)value;
  }
  const json& features = document.at("features");
  EXPECT_TRUE(features.is_array());
  std::set<uint32_t> ids;
  auto read_position = [](const json& position) {
    EXPECT_TRUE(position.is_array());
    EXPECT_EQ(position.size(), 2U);
    EXPECT_TRUE(position.at(0).is_number() && position.at(1).is_number());
    return Point2(position.at(0).get<double>(), position.at(1).get<double>());
  };
  auto read_id = [](const json& value, const char* what) {
    EXPECT_TRUE(value.is_number_unsigned()) << what << " is not an unsigned integer: " << value;
    const uint32_t id = value.get<uint32_t>();
    return id;
  };
  std::vector<json> edge_features;
  for (const json& feature : features) {
    EXPECT_EQ(feature.at("type"), "Feature");
    const json& properties = feature.at("properties");
    const json& geometry = feature.at("geometry");
    EXPECT_TRUE(properties.is_object());
    const std::string type = geometry.at("type").get<std::string>();
    if (type == "Point") {
      const uint32_t id = read_id(properties.at("id"), "a node's id");
      EXPECT_TRUE(ids.insert(id).second) << "id " << id << " is not unique";
      EXPECT_TRUE(properties.at("frame").is_string());
      EXPECT_FALSE(properties.at("frame").get<std::string>().empty());
      graph.frames[id] = properties.at("frame").get<std::string>();
      graph.nodes[id] = read_position(geometry.at("coordinates"));
    } else if (type == "MultiLineString") {
      edge_features.push_back(feature);
    } else {
      ADD_FAILURE() << "a feature of type " << type << " is neither a node nor an edge";
    }
  }
  for (const json& feature : edge_features) {
    const json& properties = feature.at("properties");
    Nav2Graph::Edge edge;
    const uint32_t id = read_id(properties.at("id"), "an edge's id");
    EXPECT_TRUE(ids.insert(id).second) << "id " << id << " is not unique";
    edge.start = read_id(properties.at("startid"), "startid");
    edge.end = read_id(properties.at("endid"), "endid");
    EXPECT_EQ(graph.nodes.count(edge.start), 1U) << "edge " << id << ": no start node";
    EXPECT_EQ(graph.nodes.count(edge.end), 1U) << "edge " << id << ": no end node";
    if (properties.contains("cost")) {
      EXPECT_TRUE(properties.at("cost").is_number());
      edge.cost = properties.at("cost").get<double>();
      EXPECT_GE(edge.cost, 0.0);
    }
    if (properties.contains("overridable")) {
      EXPECT_TRUE(properties.at("overridable").is_boolean());
    }
    if (properties.contains("metadata")) {
      EXPECT_TRUE(properties.at("metadata").is_object());
    }
    const json& lines = feature.at("geometry").at("coordinates");
    EXPECT_TRUE(lines.is_array());
    EXPECT_GE(lines.size(), 1U);
    const json& line = lines.at(0);
    EXPECT_GE(line.size(), 2U);
    if (graph.nodes.count(edge.start) != 0 && graph.nodes.count(edge.end) != 0) {
      EXPECT_EQ(read_position(line.front()), graph.nodes.at(edge.start));
      EXPECT_EQ(read_position(line.back()), graph.nodes.at(edge.end));
    }
    graph.edges[id] = edge;
  }
  return graph;
}

RouteGraph TwoRoomGraph() {
  RouteGraphBuilder builder(RouteGraphOptions{});
  StatusOr<RouteGraph> graph = builder.Build(testing::TwoRooms(1.0));
  EXPECT_TRUE(graph.ok());
  return std::move(graph).value();
}

TEST(RouteGraphExportTest, Nav2GeoJsonReadsBackStrictlyAsTheSameGraph) {
  const RouteGraph graph = TwoRoomGraph();
  ASSERT_GE(graph.edges.size(), 2U);
  // Through text, as the file is written and read.
  const json document = json::parse(Nav2RouteGeoJson(graph).dump(2));
  const Nav2Graph read = ReadNav2GraphStrictly(document);
  ASSERT_EQ(read.nodes.size(), graph.nodes.size());
  ASSERT_EQ(read.edges.size(), 2 * graph.edges.size()) << "each edge both ways";
  for (const RouteNode& node : graph.nodes) {
    ASSERT_EQ(read.nodes.count(node.id), 1U);
    EXPECT_NEAR((read.nodes.at(node.id) - node.position).norm(), 0.0, 1e-4);
    EXPECT_EQ(read.frames.at(node.id), "map");
  }
  for (const RouteEdge& edge : graph.edges) {
    ASSERT_EQ(read.edges.count(edge.id), 1U);
    ASSERT_EQ(read.edges.count(edge.reverse_id), 1U);
    const Nav2Graph::Edge& forward = read.edges.at(edge.id);
    const Nav2Graph::Edge& backward = read.edges.at(edge.reverse_id);
    EXPECT_EQ(forward.start, edge.start);
    EXPECT_EQ(forward.end, edge.end);
    EXPECT_EQ(backward.start, edge.end);
    EXPECT_EQ(backward.end, edge.start);
    EXPECT_NEAR(forward.cost, edge.length, 1e-4);
    EXPECT_NEAR(forward.cost, (read.nodes.at(edge.end) - read.nodes.at(edge.start)).norm(), 2e-4);
  }
}

TEST(RouteGraphExportTest, StrictReaderRejectsWhatNav2WouldNot) {
  json document = Nav2RouteGeoJson(TwoRoomGraph());
  // An edge whose end is no node.
  for (json& feature : document["features"]) {
    if (feature["geometry"]["type"] == "MultiLineString") {
      feature["properties"]["endid"] = 999999U;
      break;
    }
  }
  ::testing::TestPartResultArray failures;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    ReadNav2GraphStrictly(document);
  }
  ASSERT_EQ(failures.size(), 1);
  EXPECT_THAT(failures.GetTestPartResult(0).message(), ::testing::HasSubstr("no end node"));
}

TEST(RouteGraphExportTest, RmfNavGraphHasOneLevelOfNamedVerticesAndLanesBothWays) {
  const RouteGraph graph = TwoRoomGraph();
  const YAML::Node root = YAML::Load(RmfNavGraphYaml(graph, "L1"));
  ASSERT_TRUE(root["levels"].IsMap());
  ASSERT_EQ(root["levels"].size(), 1U);
  const YAML::Node level = root["levels"]["L1"];
  ASSERT_TRUE(level.IsMap());
  const YAML::Node vertices = level["vertices"];
  const YAML::Node lanes = level["lanes"];
  ASSERT_TRUE(vertices.IsSequence());
  ASSERT_TRUE(lanes.IsSequence());
  ASSERT_EQ(vertices.size(), graph.nodes.size());
  std::set<std::string> names;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const YAML::Node vertex = vertices[i];
    ASSERT_EQ(vertex.size(), 3U);
    const double x = vertex[0].as<double>();
    const double y = vertex[1].as<double>();
    EXPECT_NEAR(x, graph.nodes[i].position.x(), 1e-4);
    EXPECT_NEAR(y, graph.nodes[i].position.y(), 1e-4);
    ASSERT_TRUE(vertex[2].IsMap());
    const std::string name = vertex[2]["name"].as<std::string>();
    std::string expected = "n";
    expected.append(std::to_string(graph.nodes[i].id));
    EXPECT_EQ(name, expected);
    EXPECT_TRUE(names.insert(name).second) << "duplicate vertex name " << name;
  }
  ASSERT_EQ(lanes.size(), 2 * graph.edges.size());
  std::set<std::pair<size_t, size_t>> directed;
  for (const YAML::Node& lane : lanes) {
    ASSERT_EQ(lane.size(), 3U);
    const size_t from = lane[0].as<size_t>();
    const size_t to = lane[1].as<size_t>();
    EXPECT_LT(from, vertices.size());
    EXPECT_LT(to, vertices.size());
    EXPECT_TRUE(lane[2].IsMap());
    directed.insert({from, to});
  }
  for (const auto& [from, to] : directed) {
    EXPECT_EQ(directed.count({to, from}), 1U) << "lane " << from << " -> " << to << " one way only";
  }
  EXPECT_TRUE(root["lifts"].IsMap());
}

}  // namespace
}  // namespace fleetmap::route_graph
