#include "common/transport/idl_shapes.hpp"

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
                                 Primitive("sequence_number", 4)};
  return shape;
}

const CdrShape& VectorTileShape() {
  static const CdrShape shape = {String("robot_id"),
                                 Primitive("tile_x", 4),
                                 Primitive("tile_y", 4),
                                 Struct("stamp", TimeShape()),
                                 String("frame_id"),
                                 Primitive("revision", 4),
                                 Primitive("tile_size", 8),
                                 Primitive("quantum", 8),
                                 Primitive("epsilon", 4),
                                 Primitive("resolution", 4),
                                 Sequence("obstacle_sizes", 4),
                                 Sequence("obstacle_closed", 1),
                                 Sequence("obstacle_half_widths", 2),
                                 Sequence("obstacle_x", 2),
                                 Sequence("obstacle_y", 2),
                                 Sequence("free_polygon_rings", 4),
                                 Sequence("free_ring_sizes", 4),
                                 Sequence("free_x", 2),
                                 Sequence("free_y", 2)};
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

}  // namespace fleetmap::transport
