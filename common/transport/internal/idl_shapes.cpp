#include "common/transport/internal/idl_shapes.hpp"

namespace fleetmap::transport {
namespace {

using Kind = CdrField::Kind;

CdrField Primitive(const char* name, size_t size) {
  return {name, Kind::kPrimitive, size, nullptr};
}
CdrField String(const char* name) { return {name, Kind::kString, 1, nullptr}; }
CdrField Sequence(const char* name, size_t size) {
  return {name, Kind::kPrimitiveSequence, size, nullptr};
}
// A sequence<string> has the bytes of a sequence of structs holding one string each.
CdrField StringSequence(const char* name) {
  static const CdrShape one_string = {String("value")};
  return {name, Kind::kStructSequence, 0, &one_string};
}
CdrField Struct(const char* name, const CdrShape& shape) {
  return {name, Kind::kStruct, 0, &shape};
}

// builtin_interfaces/Time, geometry_msgs/Pose2D, Pose, std_msgs/Header, nav_msgs/MapMetaData.
const CdrShape& TimeShape() {
  static const CdrShape shape = {Primitive("sec", 4), Primitive("nanosec", 4)};
  return shape;
}
const CdrShape& Pose2DShape() {
  static const CdrShape shape = {Primitive("x", 8), Primitive("y", 8), Primitive("theta", 8)};
  return shape;
}
const CdrShape& PoseShape() {
  static const CdrShape point = {Primitive("x", 8), Primitive("y", 8), Primitive("z", 8)};
  static const CdrShape quaternion = {Primitive("x", 8), Primitive("y", 8), Primitive("z", 8),
                                      Primitive("w", 8)};
  static const CdrShape shape = {Struct("position", point), Struct("orientation", quaternion)};
  return shape;
}
const CdrShape& HeaderShape() {
  static const CdrShape shape = {Struct("stamp", TimeShape()), String("frame_id")};
  return shape;
}
const CdrShape& MapMetaDataShape() {
  static const CdrShape shape = {Struct("map_load_time", TimeShape()), Primitive("resolution", 4),
                                 Primitive("width", 4), Primitive("height", 4),
                                 Struct("origin", PoseShape())};
  return shape;
}

}  // namespace

const CdrShape& OccupancyGridShape() {
  static const CdrShape shape = {Struct("header", HeaderShape()),
                                 Struct("info", MapMetaDataShape()), Sequence("data", 1)};
  return shape;
}

const CdrShape& OccupancyGridUpdateShape() {
  static const CdrShape shape = {
      Struct("header", HeaderShape()), Primitive("x", 4),      Primitive("y", 4),
      Primitive("width", 4),           Primitive("height", 4), Sequence("data", 1)};
  return shape;
}

const CdrShape& CompressedGridUpdateShape() {
  static const CdrShape shape = {
      Struct("header", HeaderShape()), Primitive("x", 4),      Primitive("y", 4),
      Primitive("width", 4),           Primitive("height", 4), Primitive("compression", 1),
      Primitive("raw_size", 4),        Sequence("data", 1)};
  return shape;
}

const CdrShape& RobotStatusShape() {
  static const CdrShape shape = {String("robot_id"),
                                 Struct("stamp", TimeShape()),
                                 Struct("map_from_robot", Pose2DShape()),
                                 Struct("fleet_from_map", Pose2DShape()),
                                 String("map_topic"),
                                 Primitive("map_width", 4),
                                 Primitive("map_height", 4),
                                 Primitive("map_resolution", 4),
                                 Primitive("map_revision", 4),
                                 Primitive("maps_published", 8),
                                 Primitive("tiles_published", 8),
                                 Primitive("bytes_published", 8),
                                 Primitive("sequence_number", 4),
                                 Primitive("baseline_events", 8),
                                 Primitive("baseline_grid_bytes", 8),
                                 Primitive("baseline_patch_bytes", 8),
                                 Primitive("baseline_zstd3_bytes", 8),
                                 Primitive("baseline_zstd19_bytes", 8),
                                 Primitive("baseline_lz4_bytes", 8),
                                 Primitive("baseline_patches_pending", 4),
                                 Primitive("tiles_in_map_frame", 1),
                                 Primitive("fleet_from_map_given", 1)};
  return shape;
}

const CdrShape& VectorTileShape() {
  static const CdrShape shape = {
      String("robot_id"),           Primitive("tile_x", 4),         Primitive("tile_y", 4),
      Struct("stamp", TimeShape()), Primitive("layout_version", 1), Primitive("compression", 1),
      Primitive("revision", 4),     Primitive("tile_size_mm", 4),   Primitive("epsilon", 4),
      Primitive("resolution", 4),   Sequence("geometry", 1)};
  return shape;
}

const CdrShape& VectorMapShape() {
  static const CdrShape shape = {
      String("format"),
      String("frame_id"),
      Primitive("tile_size", 8),
      Primitive("epsilon", 4),
      Primitive("resolution", 4),
      CdrField{"tiles", CdrField::Kind::kStructSequence, 0, &VectorTileShape()}};
  return shape;
}

const CdrShape& VmapFormatShape() {
  static const CdrShape shape = {String("format")};
  return shape;
}

const CdrShape& EntityShape() {
  static const CdrShape shape = {
      String("robot_id"),         String("entity_id"),          Struct("stamp", TimeShape()),
      String("frame_id"),         Primitive("entity_class", 1), Sequence("x", 8),
      Sequence("y", 8),           Sequence("track_stamps", 8),  Sequence("track_headings", 8),
      Primitive("direction", 8),  Primitive("step_width", 8),   Primitive("next_floor_height", 8),
      Primitive("run_length", 8), Primitive("open", 1),         Primitive("dominant_side", 1),
      Primitive("left_view", 1),  Primitive("entered_view", 1)};
  return shape;
}

const CdrShape& SubmapShape() {
  static const CdrShape shape = {
      Primitive("submap_id", 4),  Struct("stamp", TimeShape()),
      String("frame_id"),         Primitive("kind", 1),
      Primitive("state", 1),      Primitive("place", 4),
      Primitive("elevation", 8),  Struct("fleet_from_submap", Pose2DShape()),
      String("source_robot"),     String("source_entity"),
      Primitive("precision", 4),  Primitive("observed_fraction", 4),
      Primitive("resolution", 4), Primitive("width", 4),
      Primitive("height", 4),     Struct("origin", Pose2DShape()),
      Sequence("data", 1),        Sequence("edge_to", 4),
      Sequence("edge_x", 8),      Sequence("edge_y", 8),
      Sequence("edge_theta", 8),  StringSequence("edge_entity")};
  return shape;
}

const CdrShape& ObjectTemplateShape() {
  static const CdrShape shape = {Primitive("template_id", 4),  Struct("stamp", TimeShape()),
                                 Primitive("learning_run", 4), Primitive("object_count", 4),
                                 Primitive("resolution", 4),   Primitive("width", 4),
                                 Primitive("height", 4),       Sequence("data", 1)};
  return shape;
}

const CdrShape& ObjectModelShape() {
  static const CdrShape shape = {
      Primitive("object_id", 4),   Struct("stamp", TimeShape()), Primitive("learning_run", 4),
      Primitive("template_id", 4), Primitive("resolution", 4),   Primitive("width", 4),
      Primitive("height", 4),      Sequence("data", 1),          Sequence("sighting_session", 4),
      Sequence("sighting_x", 8),   Sequence("sighting_y", 8),    Sequence("sighting_theta", 8)};
  return shape;
}

const CdrShape& RobotFrameShape() {
  static const CdrShape shape = {String("robot_id"),
                                 Struct("stamp", TimeShape()),
                                 Primitive("state", 1),
                                 Struct("fleet_from_map", Pose2DShape()),
                                 Primitive("confidence", 8),
                                 Primitive("overlap", 4),
                                 Primitive("placements", 4),
                                 String("placed_against"),
                                 Primitive("standing", 1),
                                 String("standing_reason"),
                                 Primitive("contradicted_share", 4),
                                 Primitive("contradicted_m", 4),
                                 Primitive("area_min_x", 8),
                                 Primitive("area_min_y", 8),
                                 Primitive("area_max_x", 8),
                                 Primitive("area_max_y", 8),
                                 String("waiting_reason")};
  return shape;
}

const CdrShape& RobotAdmissionShape() {
  static const CdrShape shape = {String("robot_id"), Struct("stamp", TimeShape()),
                                 String("operator_name")};
  return shape;
}

const CdrShape& FleetServerShape() {
  static const CdrShape shape = {String("server_id"),
                                 String("name"),
                                 Primitive("ownership_strength", 4),
                                 Primitive("serving", 1),
                                 Struct("started", TimeShape()),
                                 Struct("stamp", TimeShape()),
                                 Primitive("robots", 4)};
  return shape;
}

const CdrShape& RouteGraphShape() {
  static const CdrShape shape = {String("graph_id"),
                                 Struct("stamp", TimeShape()),
                                 Primitive("revision", 8),
                                 String("frame"),
                                 Primitive("robot_radius", 8),
                                 Primitive("clearance_margin", 8),
                                 Sequence("node_id", 4),
                                 Sequence("node_x", 8),
                                 Sequence("node_y", 8),
                                 Sequence("node_kind", 1),
                                 Sequence("node_clearance", 4),
                                 Sequence("edge_id", 4),
                                 Sequence("edge_reverse_id", 4),
                                 Sequence("edge_start", 4),
                                 Sequence("edge_end", 4),
                                 Sequence("edge_length", 4),
                                 Sequence("edge_clearance", 4),
                                 Sequence("node_flags", 1),
                                 Sequence("edge_flags", 1),
                                 Sequence("edge_object", 4),
                                 String("note")};
  return shape;
}

const CdrShape& TfMessageShape() {
  static const CdrShape vector3 = {Primitive("x", 8), Primitive("y", 8), Primitive("z", 8)};
  static const CdrShape quaternion = {Primitive("x", 8), Primitive("y", 8), Primitive("z", 8),
                                      Primitive("w", 8)};
  static const CdrShape transform = {Struct("translation", vector3),
                                     Struct("rotation", quaternion)};
  static const CdrShape stamped = {Struct("header", HeaderShape()), String("child_frame_id"),
                                   Struct("transform", transform)};
  static const CdrShape shape = {
      CdrField{"transforms", CdrField::Kind::kStructSequence, 0, &stamped}};
  return shape;
}

}  // namespace fleetmap::transport
