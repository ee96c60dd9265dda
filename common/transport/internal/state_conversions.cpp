#include "common/transport/internal/state_conversions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/core/number_format.hpp"
#include "common/transport/internal/conversions.hpp"

namespace fleetmap::transport {
namespace {

using fleetmap_msgs::msg::dds_::Entity_;
using fleetmap_msgs::msg::dds_::FleetServer_;
using fleetmap_msgs::msg::dds_::ObjectModel_;
using fleetmap_msgs::msg::dds_::ObjectTemplate_;
using fleetmap_msgs::msg::dds_::RobotAdmission_;
using fleetmap_msgs::msg::dds_::RobotFrame_;
using fleetmap_msgs::msg::dds_::RouteGraph_;
using fleetmap_msgs::msg::dds_::Submap_;

// Ids are names a log can print: bounded, printable, no spaces.
constexpr size_t kMaxIdLength = 128;
// A reason is a sentence for people.
constexpr size_t kMaxReasonLength = 1024;
// A patch or a predicted sub-map is a local thing: refuse grids beyond this many cells.
constexpr uint64_t kMaxCells = 64ull * 1024 * 1024;

Status CheckId(const std::string& id, const char* what) {
  if (id.empty() || id.size() > kMaxIdLength) {
    return InvalidArgumentError(std::string(what) + " must have 1 to " +
                                std::to_string(kMaxIdLength) + " characters");
  }
  const bool printable =
      std::all_of(id.begin(), id.end(), [](char c) { return c > ' ' && c < 127; });
  if (!printable) return InvalidArgumentError(std::string(what) + " has unprintable characters");
  return Status::Ok();
}

bool AllFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

Vector2 Direction(double radians) { return {std::cos(radians), std::sin(radians)}; }
double Angle(const Vector2& direction) { return std::atan2(direction.y(), direction.x()); }

// Checks a grid header against its data: positive finite resolution, width * height cells.
Status CheckGrid(float resolution, uint32_t width, uint32_t height, size_t data_size) {
  if (!std::isfinite(resolution) || resolution <= 0.0F) {
    return InvalidArgumentError("resolution " + std::to_string(resolution) + " is not positive");
  }
  // A side of 0 makes any other side hold no cells: each side must also fit the grid's int.
  if (width > static_cast<uint32_t>(std::numeric_limits<int32_t>::max()) ||
      height > static_cast<uint32_t>(std::numeric_limits<int32_t>::max())) {
    return InvalidArgumentError(std::to_string(width) + " x " + std::to_string(height) +
                                " cells: a side is larger than a grid can be");
  }
  const uint64_t cells = static_cast<uint64_t>(width) * height;
  if (cells > kMaxCells) {
    return InvalidArgumentError(std::to_string(width) + " x " + std::to_string(height) +
                                " cells is more than the limit of " + std::to_string(kMaxCells));
  }
  if (cells != data_size) {
    return InvalidArgumentError(std::to_string(width) + " x " + std::to_string(height) +
                                " cells but " + std::to_string(data_size) + " values");
  }
  return Status::Ok();
}

std::vector<int8_t> ToPercent(const std::vector<float>& occupancy) {
  std::vector<int8_t> data(occupancy.size());
  std::transform(occupancy.begin(), occupancy.end(), data.begin(), [](float p) {
    return static_cast<int8_t>(std::lround(std::clamp(p, 0.0F, 1.0F) * 100.0F));
  });
  return data;
}

// ObjectTemplate_ and ObjectModel_ carry a patch in the same fields.
template <typename Sample>
void SetPatch(const scene::Patch& patch, Sample& sample) {
  sample.resolution(static_cast<float>(patch.resolution));
  sample.width(static_cast<uint32_t>(patch.width));
  sample.height(static_cast<uint32_t>(patch.height));
  sample.data(ToPercent(patch.occupancy));
}

template <typename Sample>
StatusOr<scene::Patch> PatchOf(const Sample& sample) {
  const float resolution = sample.resolution();
  const uint32_t width = sample.width();
  const uint32_t height = sample.height();
  const std::vector<int8_t>& data = sample.data();
  FLEETMAP_RETURN_IF_ERROR(CheckGrid(resolution, width, height, data.size()));
  scene::Patch patch;
  patch.width = static_cast<int>(width);
  patch.height = static_cast<int>(height);
  patch.resolution = DoubleFromFloat(resolution);
  patch.occupancy.reserve(data.size());
  for (const int8_t value : data) {
    if (value < 0 || value > 100) {
      return InvalidArgumentError("patch value " + std::to_string(value) + " is not in 0..100");
    }
    patch.occupancy.push_back(static_cast<float>(value) / 100.0F);
  }
  return patch;
}

void SetPoints(Entity_& sample, const std::vector<Point2>& points) {
  std::vector<double> x;
  std::vector<double> y;
  for (const Point2& point : points) {
    x.push_back(point.x());
    y.push_back(point.y());
  }
  sample.x(std::move(x));
  sample.y(std::move(y));
}

struct EntityToIdl {
  Entity_& sample;

  void operator()(const scene::DoorEntity& door) const {
    sample.entity_class(kEntityDoor);
    SetPoints(sample, {door.hinge, door.latch});
    sample.direction(Angle(door.opening_direction));
    sample.open(door.open);
  }
  void operator()(const scene::StairsEntity& stairs) const {
    sample.entity_class(kEntityStairs);
    SetPoints(sample, {stairs.position});
    sample.direction(Angle(stairs.ascending));
    sample.step_width(stairs.step_width);
    sample.next_floor_height(stairs.next_floor_height);
    sample.run_length(stairs.run_length);
  }
  void operator()(const scene::PersonTrack& track) const {
    sample.entity_class(kEntityPerson);
    std::vector<Point2> points;
    std::vector<double> stamps;
    std::vector<double> headings;
    for (const scene::TrackPoint& point : track.points) {
      points.push_back(point.position);
      stamps.push_back(point.stamp);
      headings.push_back(point.heading);
    }
    SetPoints(sample, points);
    sample.track_stamps(std::move(stamps));
    sample.track_headings(std::move(headings));
    sample.dominant_side(static_cast<int8_t>(track.dominant_side));
    sample.left_view(track.left_view);
    sample.entered_view(track.entered_view);
  }
};

StatusOr<scene::Entity> EntityFromIdl(const Entity_& sample) {
  const std::vector<double>& x = sample.x();
  const std::vector<double>& y = sample.y();
  if (x.size() != y.size()) {
    return InvalidArgumentError(std::to_string(x.size()) + " x values but " +
                                std::to_string(y.size()) + " y values");
  }
  if (!AllFinite(x) || !AllFinite(y) || !std::isfinite(sample.direction())) {
    return InvalidArgumentError("a coordinate or the direction is not finite");
  }
  switch (sample.entity_class()) {
    case kEntityDoor: {
      if (x.size() != 2) {
        return InvalidArgumentError("a door needs 2 points (hinge, latch), got " +
                                    std::to_string(x.size()));
      }
      scene::DoorEntity door;
      door.id = sample.entity_id();
      door.hinge = {x[0], y[0]};
      door.latch = {x[1], y[1]};
      if ((door.latch - door.hinge).norm() <= 1e-6) {
        return InvalidArgumentError("a door of zero width");
      }
      door.opening_direction = Direction(sample.direction());
      door.open = sample.open();
      return scene::Entity(door);
    }
    case kEntityStairs: {
      if (x.size() != 1) {
        return InvalidArgumentError("stairs need 1 point, got " + std::to_string(x.size()));
      }
      if (!std::isfinite(sample.step_width()) || sample.step_width() <= 0.0 ||
          !std::isfinite(sample.next_floor_height()) || !std::isfinite(sample.run_length()) ||
          sample.run_length() < 0.0) {
        return InvalidArgumentError(
            "stairs need a positive step width, a finite height and a run length >= 0");
      }
      scene::StairsEntity stairs;
      stairs.id = sample.entity_id();
      stairs.position = {x[0], y[0]};
      stairs.ascending = Direction(sample.direction());
      stairs.step_width = sample.step_width();
      stairs.next_floor_height = sample.next_floor_height();
      stairs.run_length = sample.run_length();
      return scene::Entity(stairs);
    }
    case kEntityPerson: {
      const std::vector<double>& stamps = sample.track_stamps();
      const std::vector<double>& headings = sample.track_headings();
      if (x.empty() || stamps.size() != x.size() || headings.size() != x.size()) {
        return InvalidArgumentError("a track needs as many stamps and headings as points (" +
                                    std::to_string(x.size()) + " points, " +
                                    std::to_string(stamps.size()) + " stamps, " +
                                    std::to_string(headings.size()) + " headings)");
      }
      if (!AllFinite(stamps) || !AllFinite(headings)) {
        return InvalidArgumentError("a track stamp or heading is not finite");
      }
      if (!std::is_sorted(stamps.begin(), stamps.end())) {
        return InvalidArgumentError("track stamps are not increasing");
      }
      if (sample.dominant_side() < -1 || sample.dominant_side() > 1) {
        return InvalidArgumentError("dominant side " + std::to_string(sample.dominant_side()) +
                                    " is not -1, 0 or +1");
      }
      scene::PersonTrack track;
      track.id = sample.entity_id();
      for (size_t i = 0; i < x.size(); ++i) {
        track.points.push_back({stamps[i], Point2(x[i], y[i]), headings[i]});
      }
      track.dominant_side = sample.dominant_side();
      track.left_view = sample.left_view();
      track.entered_view = sample.entered_view();
      return scene::Entity(track);
    }
    default:
      return InvalidArgumentError("unknown entity class " +
                                  std::to_string(static_cast<int>(sample.entity_class())));
  }
}

// A frame a reader can use: a robot name, finite numbers in range.
Status CheckRobotFrame(const RobotFrameMessage& message) {
  if (!IsValidRobotName(message.robot.value)) {
    return InvalidArgumentError("RobotFrame robot_id \"" + message.robot.value.substr(0, 80) +
                                "\" is not a valid robot name");
  }
  if (!message.fleet_from_map.finite()) {
    return InvalidArgumentError("RobotFrame of " + message.robot.value +
                                " has a non-finite fleet_from_map");
  }
  if (!(message.confidence >= 0.0 && message.confidence <= 1.0) ||
      !(message.overlap >= 0.0 && message.overlap <= 1.0)) {
    return InvalidArgumentError("RobotFrame of " + message.robot.value +
                                " has a confidence or overlap outside [0, 1]");
  }
  if (message.placed_against.size() > kMaxIdLength) {
    return InvalidArgumentError("RobotFrame of " + message.robot.value +
                                " has a placed_against longer than " +
                                std::to_string(kMaxIdLength) + " characters");
  }
  if (message.standing_reason.size() > kMaxReasonLength ||
      message.waiting_reason.size() > kMaxReasonLength) {
    return InvalidArgumentError("RobotFrame of " + message.robot.value +
                                " has a standing_reason or waiting_reason longer than " +
                                std::to_string(kMaxReasonLength) + " characters");
  }
  if (!(message.contradicted_share >= 0.0 && message.contradicted_share <= 1.0) ||
      !(message.contradicted_m >= 0.0 && std::isfinite(message.contradicted_m)) ||
      !message.area_min.allFinite() || !message.area_max.allFinite()) {
    return InvalidArgumentError("RobotFrame of " + message.robot.value +
                                " has contradiction figures out of range");
  }
  return Status::Ok();
}

}  // namespace

StatusOr<Entity_> ToIdl(const EntityMessage& message) {
  Entity_ sample;
  sample.robot_id(message.robot.value);
  sample.entity_id(message.entity_id());
  sample.stamp(ToIdl(message.stamp));
  sample.frame_id(message.frame_id);
  std::visit(EntityToIdl{sample}, message.entity);
  return sample;
}

StatusOr<EntityMessage> FromIdl(const Entity_& sample) {
  if (!IsValidRobotName(sample.robot_id())) {
    return InvalidArgumentError("robot id \"" + sample.robot_id().substr(0, 64) +
                                "\" is not a ROS 2 name");
  }
  FLEETMAP_RETURN_IF_ERROR(CheckId(sample.entity_id(), "entity id"));
  StatusOr<scene::Entity> entity = EntityFromIdl(sample);
  if (!entity.ok()) {
    return entity.status().WithContext("entity " + sample.entity_id() + " of " + sample.robot_id());
  }
  EntityMessage message;
  message.robot = RobotId{sample.robot_id()};
  message.stamp = FromIdl(sample.stamp());
  message.frame_id = sample.frame_id();
  message.entity = *std::move(entity);
  return message;
}

StatusOr<Submap_> ToIdl(const SubmapMessage& message) {
  const scene::Submap& submap = message.submap;
  Submap_ sample;
  sample.submap_id(submap.id);
  sample.stamp(ToIdl(message.stamp));
  sample.frame_id("fleet");
  sample.kind(static_cast<uint8_t>(submap.kind));
  sample.state(static_cast<uint8_t>(message.state));
  sample.place(submap.place);
  sample.elevation(submap.elevation);
  sample.fleet_from_submap(ToIdl(submap.map_from_submap));
  sample.source_robot(message.source_robot.value);
  sample.source_entity(message.source_entity);
  sample.precision(message.precision);
  sample.observed_fraction(message.observed_fraction);
  const grid::OccupancyGrid& cells = submap.navigable;
  sample.resolution(static_cast<float>(cells.resolution()));
  sample.width(static_cast<uint32_t>(cells.width()));
  sample.height(static_cast<uint32_t>(cells.height()));
  sample.origin(ToIdl(cells.origin()));
  sample.data(cells.data());
  std::vector<uint32_t> to;
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> theta;
  std::vector<std::string> entity;
  for (const scene::SubmapEdge& edge : message.edges) {
    to.push_back(edge.to);
    x.push_back(edge.from_T_to.x);
    y.push_back(edge.from_T_to.y);
    theta.push_back(edge.from_T_to.yaw);
    entity.push_back(edge.entity_id);
  }
  sample.edge_to(std::move(to));
  sample.edge_x(std::move(x));
  sample.edge_y(std::move(y));
  sample.edge_theta(std::move(theta));
  sample.edge_entity(std::move(entity));
  return sample;
}

StatusOr<SubmapMessage> FromIdl(const Submap_& sample) {
  const std::string name = "sub-map " + std::to_string(sample.submap_id());
  if (sample.kind() > static_cast<uint8_t>(scene::SubmapKind::kPredictedDoor)) {
    return InvalidArgumentError(name + ": unknown kind " + std::to_string(sample.kind()));
  }
  if (sample.state() > static_cast<uint8_t>(scene::SubmapState::kRetracted)) {
    return InvalidArgumentError(name + ": unknown state " + std::to_string(sample.state()));
  }
  if (Status grid =
          CheckGrid(sample.resolution(), sample.width(), sample.height(), sample.data().size());
      !grid.ok()) {
    return grid.WithContext(name);
  }
  const size_t edges = sample.edge_to().size();
  if (sample.edge_x().size() != edges || sample.edge_y().size() != edges ||
      sample.edge_theta().size() != edges || sample.edge_entity().size() != edges) {
    return InvalidArgumentError(name + ": edge arrays of different lengths");
  }
  const Pose2 fleet_from_submap = FromIdl(sample.fleet_from_submap());
  const Pose2 origin = FromIdl(sample.origin());
  if (!AllFinite({fleet_from_submap.x, fleet_from_submap.y, fleet_from_submap.yaw, origin.x,
                  origin.y, origin.yaw, sample.elevation()}) ||
      !AllFinite(sample.edge_x()) || !AllFinite(sample.edge_y()) ||
      !AllFinite(sample.edge_theta())) {
    return InvalidArgumentError(name + ": a pose is not finite");
  }
  SubmapMessage message;
  scene::Submap& submap = message.submap;
  submap.id = sample.submap_id();
  submap.kind = static_cast<scene::SubmapKind>(sample.kind());
  submap.place = sample.place();
  submap.elevation = sample.elevation();
  submap.map_from_submap = fleet_from_submap;
  submap.navigable =
      grid::OccupancyGrid(static_cast<int>(sample.width()), static_cast<int>(sample.height()),
                          DoubleFromFloat(sample.resolution()), origin);
  submap.navigable.mutable_data() = sample.data();
  if (!sample.source_entity().empty()) submap.entity_ids.push_back(sample.source_entity());
  message.state = static_cast<scene::SubmapState>(sample.state());
  message.source_robot = RobotId{sample.source_robot()};
  message.source_entity = sample.source_entity();
  message.precision = sample.precision();
  message.observed_fraction = sample.observed_fraction();
  for (size_t k = 0; k < edges; ++k) {
    scene::SubmapEdge edge;
    edge.from = submap.id;
    edge.to = sample.edge_to()[k];
    edge.from_T_to = Pose2{sample.edge_x()[k], sample.edge_y()[k], sample.edge_theta()[k]};
    edge.entity_id = sample.edge_entity()[k].substr(0, kMaxIdLength * 2 + 1);
    message.edges.push_back(std::move(edge));
  }
  message.stamp = FromIdl(sample.stamp());
  return message;
}

StatusOr<ObjectTemplate_> ToIdl(const ObjectTemplateMessage& message) {
  ObjectTemplate_ sample;
  sample.template_id(message.template_id);
  sample.stamp(ToIdl(message.stamp));
  sample.learning_run(message.learning_run);
  sample.object_count(message.object_count);
  SetPatch(message.patch, sample);
  return sample;
}

StatusOr<ObjectTemplateMessage> FromIdl(const ObjectTemplate_& sample) {
  StatusOr<scene::Patch> patch = PatchOf(sample);
  if (!patch.ok()) {
    return patch.status().WithContext("template " + std::to_string(sample.template_id()));
  }
  ObjectTemplateMessage message;
  message.template_id = sample.template_id();
  message.learning_run = sample.learning_run();
  message.object_count = sample.object_count();
  message.patch = *std::move(patch);
  message.stamp = FromIdl(sample.stamp());
  return message;
}

StatusOr<ObjectModel_> ToIdl(const ObjectModelMessage& message) {
  ObjectModel_ sample;
  sample.object_id(message.object_id);
  sample.stamp(ToIdl(message.stamp));
  sample.learning_run(message.learning_run);
  sample.template_id(message.template_id);
  SetPatch(message.patch, sample);
  for (const ObjectSighting& sighting : message.sightings) {
    sample.sighting_session().push_back(sighting.session);
    sample.sighting_x().push_back(sighting.fleet_from_object.x);
    sample.sighting_y().push_back(sighting.fleet_from_object.y);
    sample.sighting_theta().push_back(sighting.fleet_from_object.yaw);
  }
  return sample;
}

StatusOr<ObjectModelMessage> FromIdl(const ObjectModel_& sample) {
  const std::string name = "object " + std::to_string(sample.object_id());
  StatusOr<scene::Patch> patch = PatchOf(sample);
  if (!patch.ok()) return patch.status().WithContext(name);
  const size_t sightings = sample.sighting_session().size();
  if (sample.sighting_x().size() != sightings || sample.sighting_y().size() != sightings ||
      sample.sighting_theta().size() != sightings) {
    return InvalidArgumentError(name + ": sighting arrays of different lengths");
  }
  if (!AllFinite(sample.sighting_x()) || !AllFinite(sample.sighting_y()) ||
      !AllFinite(sample.sighting_theta())) {
    return InvalidArgumentError(name + ": a sighting pose is not finite");
  }
  ObjectModelMessage message;
  message.object_id = sample.object_id();
  message.learning_run = sample.learning_run();
  message.template_id = sample.template_id();
  message.patch = *std::move(patch);
  for (size_t k = 0; k < sightings; ++k) {
    message.sightings.push_back(
        {sample.sighting_session()[k],
         Pose2{sample.sighting_x()[k], sample.sighting_y()[k], sample.sighting_theta()[k]}});
  }
  message.stamp = FromIdl(sample.stamp());
  return message;
}

// A route graph on the wire: bounded, ids unique across nodes and edges, edges between its nodes.
constexpr size_t kMaxRouteGraphElements = 1'000'000;
// RouteGraph.idl's node_flags and edge_flags bits.
constexpr uint8_t kRoutePredicted = 1;
constexpr uint8_t kRouteBlockedByObject = 2;

StatusOr<RouteGraph_> ToIdl(const RouteGraphMessage& message) {
  FLEETMAP_RETURN_IF_ERROR(CheckId(message.graph_id, "RouteGraph graph_id"));
  const route_graph::RouteGraph& graph = message.graph;
  if (graph.nodes.size() + graph.edges.size() > kMaxRouteGraphElements) {
    return InvalidArgumentError("route graph " + message.graph_id + " has more than " +
                                std::to_string(kMaxRouteGraphElements) + " nodes and edges");
  }
  RouteGraph_ sample;
  sample.graph_id(message.graph_id);
  sample.stamp(ToIdl(message.stamp));
  sample.revision(message.revision);
  sample.frame(graph.frame);
  sample.robot_radius(graph.robot_radius);
  sample.clearance_margin(graph.clearance_margin);
  for (const route_graph::RouteNode& node : graph.nodes) {
    sample.node_id().push_back(node.id);
    sample.node_x().push_back(node.position.x());
    sample.node_y().push_back(node.position.y());
    sample.node_kind().push_back(static_cast<uint8_t>(node.kind));
    sample.node_clearance().push_back(static_cast<float>(node.clearance));
    sample.node_flags().push_back(node.predicted ? kRoutePredicted : 0);
  }
  for (const route_graph::RouteEdge& edge : graph.edges) {
    sample.edge_id().push_back(edge.id);
    sample.edge_reverse_id().push_back(edge.reverse_id);
    sample.edge_start().push_back(edge.start);
    sample.edge_end().push_back(edge.end);
    sample.edge_length().push_back(static_cast<float>(edge.length));
    sample.edge_clearance().push_back(static_cast<float>(edge.clearance));
    sample.edge_flags().push_back(
        static_cast<uint8_t>((edge.predicted ? kRoutePredicted : 0) |
                             (edge.blocking_object ? kRouteBlockedByObject : 0)));
    sample.edge_object().push_back(edge.blocking_object.value_or(0));
  }
  sample.note(graph.message.substr(0, kMaxReasonLength));
  return sample;
}

StatusOr<RouteGraphMessage> FromIdl(const RouteGraph_& sample) {
  FLEETMAP_RETURN_IF_ERROR(CheckId(sample.graph_id(), "RouteGraph graph_id"));
  const std::string name = "route graph " + sample.graph_id();
  const size_t nodes = sample.node_id().size();
  const size_t edges = sample.edge_id().size();
  if (sample.node_x().size() != nodes || sample.node_y().size() != nodes ||
      sample.node_kind().size() != nodes || sample.node_clearance().size() != nodes ||
      sample.node_flags().size() != nodes) {
    return InvalidArgumentError(name + ": node arrays of different lengths");
  }
  if (sample.edge_reverse_id().size() != edges || sample.edge_start().size() != edges ||
      sample.edge_end().size() != edges || sample.edge_length().size() != edges ||
      sample.edge_clearance().size() != edges || sample.edge_flags().size() != edges ||
      sample.edge_object().size() != edges) {
    return InvalidArgumentError(name + ": edge arrays of different lengths");
  }
  if (nodes + edges > kMaxRouteGraphElements) {
    return InvalidArgumentError(name + ": too many nodes and edges");
  }
  if (!AllFinite(sample.node_x()) || !AllFinite(sample.node_y()) ||
      !std::isfinite(sample.robot_radius()) || !std::isfinite(sample.clearance_margin())) {
    return InvalidArgumentError(name + ": a position or radius is not finite");
  }
  if (sample.frame().empty() || sample.frame().size() > kMaxIdLength) {
    return InvalidArgumentError(name + ": bad frame");
  }
  if (sample.note().size() > kMaxReasonLength) {
    return InvalidArgumentError(name + ": note longer than " + std::to_string(kMaxReasonLength));
  }
  RouteGraphMessage message;
  message.graph_id = sample.graph_id();
  message.revision = sample.revision();
  message.stamp = FromIdl(sample.stamp());
  route_graph::RouteGraph& graph = message.graph;
  graph.frame = sample.frame();
  graph.robot_radius = sample.robot_radius();
  graph.clearance_margin = sample.clearance_margin();
  graph.message = sample.note();
  std::vector<uint32_t> ids;
  for (size_t k = 0; k < nodes; ++k) {
    if (sample.node_kind()[k] > static_cast<uint8_t>(route_graph::RouteNodeKind::kLane)) {
      return InvalidArgumentError(name + ": node " + std::to_string(sample.node_id()[k]) +
                                  " has an unknown kind");
    }
    route_graph::RouteNode node;
    node.id = sample.node_id()[k];
    node.position = Point2(sample.node_x()[k], sample.node_y()[k]);
    node.kind = static_cast<route_graph::RouteNodeKind>(sample.node_kind()[k]);
    node.clearance = sample.node_clearance()[k];
    if ((sample.node_flags()[k] & ~kRoutePredicted) != 0) {
      return InvalidArgumentError(name + ": node " + std::to_string(node.id) +
                                  " has unknown flags");
    }
    node.predicted = (sample.node_flags()[k] & kRoutePredicted) != 0;
    graph.nodes.push_back(node);
    ids.push_back(node.id);
  }
  std::sort(
      graph.nodes.begin(), graph.nodes.end(),
      [](const route_graph::RouteNode& a, const route_graph::RouteNode& b) { return a.id < b.id; });
  for (size_t k = 0; k < edges; ++k) {
    route_graph::RouteEdge edge;
    edge.id = sample.edge_id()[k];
    edge.reverse_id = sample.edge_reverse_id()[k];
    edge.start = sample.edge_start()[k];
    edge.end = sample.edge_end()[k];
    edge.length = sample.edge_length()[k];
    edge.clearance = sample.edge_clearance()[k];
    const uint8_t flags = sample.edge_flags()[k];
    if ((flags & ~(kRoutePredicted | kRouteBlockedByObject)) != 0) {
      return InvalidArgumentError(name + ": edge " + std::to_string(edge.id) +
                                  " has unknown flags");
    }
    edge.predicted = (flags & kRoutePredicted) != 0;
    if ((flags & kRouteBlockedByObject) != 0) edge.blocking_object = sample.edge_object()[k];
    if (!graph.FindNode(edge.start) || !graph.FindNode(edge.end)) {
      return InvalidArgumentError(name + ": edge " + std::to_string(edge.id) +
                                  " joins a node it does not have");
    }
    graph.edges.push_back(edge);
    ids.push_back(edge.id);
    ids.push_back(edge.reverse_id);
  }
  std::sort(
      graph.edges.begin(), graph.edges.end(),
      [](const route_graph::RouteEdge& a, const route_graph::RouteEdge& b) { return a.id < b.id; });
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) {
    return InvalidArgumentError(name + ": an id names two nodes or edges");
  }
  return message;
}

StatusOr<RobotFrame_> ToIdl(const RobotFrameMessage& message) {
  FLEETMAP_RETURN_IF_ERROR(CheckRobotFrame(message));
  RobotFrame_ sample;
  sample.robot_id(message.robot.value);
  sample.stamp(ToIdl(message.stamp));
  sample.state(static_cast<uint8_t>(message.state));
  sample.fleet_from_map(ToIdl(message.fleet_from_map));
  sample.confidence(message.confidence);
  sample.overlap(static_cast<float>(message.overlap));
  sample.placements(message.placements);
  sample.placed_against(message.placed_against);
  sample.standing(static_cast<uint8_t>(message.standing));
  sample.standing_reason(message.standing_reason);
  sample.contradicted_share(static_cast<float>(message.contradicted_share));
  sample.contradicted_m(static_cast<float>(message.contradicted_m));
  sample.area_min_x(message.area_min.x());
  sample.area_min_y(message.area_min.y());
  sample.area_max_x(message.area_max.x());
  sample.area_max_y(message.area_max.y());
  sample.waiting_reason(message.waiting_reason);
  return sample;
}

StatusOr<RobotFrameMessage> FromIdl(const RobotFrame_& sample) {
  if (sample.state() > static_cast<uint8_t>(RobotFrameMessage::State::kAnchor)) {
    return InvalidArgumentError("RobotFrame of \"" + sample.robot_id().substr(0, 80) +
                                "\" has state " + std::to_string(sample.state()) +
                                " (known: 0 to 4)");
  }
  RobotFrameMessage message;
  message.robot = RobotId{sample.robot_id()};
  message.stamp = FromIdl(sample.stamp());
  message.state = static_cast<RobotFrameMessage::State>(sample.state());
  message.fleet_from_map = FromIdl(sample.fleet_from_map());
  message.confidence = sample.confidence();
  message.overlap = sample.overlap();
  message.placements = sample.placements();
  message.placed_against = sample.placed_against();
  if (sample.standing() > static_cast<uint8_t>(RobotFrameMessage::Standing::kAdmitted)) {
    return InvalidArgumentError("RobotFrame of \"" + sample.robot_id().substr(0, 80) +
                                "\" has standing " + std::to_string(sample.standing()) +
                                " (known: 0 to 2)");
  }
  message.standing = static_cast<RobotFrameMessage::Standing>(sample.standing());
  message.standing_reason = sample.standing_reason();
  message.contradicted_share = sample.contradicted_share();
  message.contradicted_m = sample.contradicted_m();
  message.area_min = Point2(sample.area_min_x(), sample.area_min_y());
  message.area_max = Point2(sample.area_max_x(), sample.area_max_y());
  message.waiting_reason = sample.waiting_reason();
  FLEETMAP_RETURN_IF_ERROR(CheckRobotFrame(message));
  return message;
}

StatusOr<RobotAdmission_> ToIdl(const RobotAdmissionMessage& message) {
  if (!IsValidRobotName(message.robot.value)) {
    return InvalidArgumentError("RobotAdmission robot_id \"" + message.robot.value.substr(0, 80) +
                                "\" is not a valid robot name");
  }
  RobotAdmission_ sample;
  sample.robot_id(message.robot.value);
  sample.stamp(ToIdl(message.stamp));
  sample.operator_name(message.operator_name.substr(0, kMaxIdLength));
  return sample;
}

StatusOr<RobotAdmissionMessage> FromIdl(const RobotAdmission_& sample) {
  if (!IsValidRobotName(sample.robot_id())) {
    return InvalidArgumentError("RobotAdmission robot_id \"" + sample.robot_id().substr(0, 80) +
                                "\" is not a valid robot name");
  }
  if (sample.operator_name().size() > kMaxIdLength) {
    return InvalidArgumentError("RobotAdmission of " + sample.robot_id() +
                                " has an operator_name longer than " +
                                std::to_string(kMaxIdLength) + " characters");
  }
  RobotAdmissionMessage message;
  message.robot = RobotId{sample.robot_id()};
  message.stamp = FromIdl(sample.stamp());
  message.operator_name = sample.operator_name();
  return message;
}

// A server's name: printable, at most kMaxIdLength characters (spaces allowed).
Status CheckServerName(const std::string& name) {
  if (name.size() > kMaxIdLength) {
    return InvalidArgumentError("FleetServer name longer than " + std::to_string(kMaxIdLength) +
                                " characters");
  }
  const bool printable =
      std::all_of(name.begin(), name.end(), [](char c) { return c >= ' ' && c < 127; });
  if (!printable) return InvalidArgumentError("FleetServer name has unprintable characters");
  return Status::Ok();
}

StatusOr<FleetServer_> ToIdl(const FleetServerMessage& message) {
  FLEETMAP_RETURN_IF_ERROR(CheckId(message.server_id, "FleetServer server_id"));
  FLEETMAP_RETURN_IF_ERROR(CheckServerName(message.name));
  FleetServer_ sample;
  sample.server_id(message.server_id);
  sample.name(message.name);
  sample.ownership_strength(message.ownership_strength);
  sample.serving(message.serving);
  sample.started(ToIdl(message.started));
  sample.stamp(ToIdl(message.stamp));
  sample.robots(message.robots);
  sample.shard(message.shard);
  sample.region_min_x(message.region[0]);
  sample.region_min_y(message.region[1]);
  sample.region_max_x(message.region[2]);
  sample.region_max_y(message.region[3]);
  return sample;
}

StatusOr<FleetServerMessage> FromIdl(const FleetServer_& sample) {
  FLEETMAP_RETURN_IF_ERROR(CheckId(sample.server_id(), "FleetServer server_id"));
  FLEETMAP_RETURN_IF_ERROR(CheckServerName(sample.name()));
  if (sample.ownership_strength() < 0) {
    return InvalidArgumentError("FleetServer " + sample.server_id() + " has ownership_strength " +
                                std::to_string(sample.ownership_strength()) + " (< 0)");
  }
  FleetServerMessage message;
  message.server_id = sample.server_id();
  message.name = sample.name();
  message.ownership_strength = sample.ownership_strength();
  message.serving = sample.serving();
  message.started = FromIdl(sample.started());
  message.stamp = FromIdl(sample.stamp());
  message.robots = sample.robots();
  if (!sample.shard().empty() && !IsValidRobotName(sample.shard())) {
    return InvalidArgumentError("FleetServer " + sample.server_id() +
                                " names a shard that is not a ROS name token");
  }
  message.shard = sample.shard();
  message.region = {sample.region_min_x(), sample.region_min_y(), sample.region_max_x(),
                    sample.region_max_y()};
  if (!std::all_of(message.region.begin(), message.region.end(),
                   [](double v) { return std::isfinite(v); })) {
    return InvalidArgumentError("FleetServer " + sample.server_id() +
                                " has a region that is not "
                                "finite");
  }
  return message;
}

}  // namespace fleetmap::transport
